// Tests of tessera::EnergyModel: counters to energy on cases computed by
// hand, static energy alone without activity, energy additive over
// intervals (frames), and the refusal of negative and non-finite
// parameters with an error naming the key.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "power/energy_model.h"

namespace {

using tessera::activity_difference;
using tessera::Config;
using tessera::ConfigError;
using tessera::EnergyActivity;
using tessera::EnergyModel;
using tessera::UnitActivity;
using tessera::UnitEnergy;

// One unit, two event classes: 2 pJ and 0.5 pJ per event, 1 mW static.
EnergyModel two_event_model() {
  return EnergyModel({{"block", {{"reads", 2.0}, {"cycles", 0.5}}, 1.0}});
}

TEST(EnergyModel, CountersToEnergyByHand) {
  // 1000 x 2 pJ = 2 nJ; 4000 x 0.5 pJ = 2 nJ; 1 mW x 1 ms = 1 uJ.
  const UnitEnergy e = two_event_model().energy(UnitActivity{"block", {{"reads", 1000}, {"cycles", 4000}}}, 1e-3);
  EXPECT_DOUBLE_EQ(e.event_joules.at("reads"), 2e-9);
  EXPECT_DOUBLE_EQ(e.event_joules.at("cycles"), 2e-9);
  EXPECT_DOUBLE_EQ(e.static_joules, 1e-6);
  EXPECT_DOUBLE_EQ(e.dynamic_joules(), 4e-9);
  EXPECT_DOUBLE_EQ(e.total_joules(), 1.004e-6);
}

TEST(EnergyModel, ZeroActivityGivesStaticEnergyOnly) {
  const UnitEnergy e = two_event_model().energy(UnitActivity{"block", {{"reads", 0}, {"cycles", 0}}}, 0.25);
  EXPECT_DOUBLE_EQ(e.dynamic_joules(), 0.0);
  EXPECT_DOUBLE_EQ(e.total_joules(), 0.25e-3);
  const UnitEnergy none = two_event_model().energy(UnitActivity{"block", {}}, 0.25);
  EXPECT_DOUBLE_EQ(none.total_joules(), 0.25e-3);
}

TEST(EnergyModel, EnergyIsAdditiveOverFrames) {
  // Snapshots at the start of the run, after frame 0 and after frame 1.
  const EnergyActivity start = {{"block", {{"reads", 0}, {"cycles", 0}}}};
  const EnergyActivity after_0 = {{"block", {{"reads", 1234}, {"cycles", 99}}}};
  const EnergyActivity after_1 = {{"block", {{"reads", 5000}, {"cycles", 1000}}}};
  const EnergyModel model = two_event_model();
  const double frame_0 = model.unit_energies(activity_difference(after_0, start), 0.010)[0].total_joules();
  const double frame_1 = model.unit_energies(activity_difference(after_1, after_0), 0.015)[0].total_joules();
  const double whole = model.unit_energies(after_1, 0.025)[0].total_joules();
  EXPECT_NEAR(frame_0 + frame_1, whole, 1e-18);
  EXPECT_DOUBLE_EQ(activity_difference(after_1, after_0)[0].counts.at("reads"), 3766);
}

TEST(EnergyModel, NegativeOrNonFiniteParameterIsAConfigurationError) {
  for (double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    try {
      const EnergyModel model({{"block", {{"reads", bad}}, 0}});
      FAIL() << "accepted " << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("power.block.reads_pj"), std::string::npos) << e.what();
    }
    EXPECT_THROW(EnergyModel({{"block", {}, bad}}), ConfigError);
  }
}

TEST(EnergyModel, BadValuesInTheConfigurationAreRefusedByKey) {
  for (const char* bad : {"-0.5", "nan", "inf", "1e400"}) {
    Config config({EnergyModel::parameters()});
    try {
      config.apply_override(std::string("power.host.busy_cycles_pj=") + bad);
      FAIL() << "accepted " << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("power.host.busy_cycles_pj"), std::string::npos) << e.what();
    }
  }
}

TEST(EnergyModel, UnknownUnitOrEventIsAProgrammingError) {
  EXPECT_THROW(two_event_model().energy(UnitActivity{"other", {}}, 1), std::logic_error);
  EXPECT_THROW(two_event_model().energy(UnitActivity{"block", {{"writes", 1}}}, 1), std::logic_error);
}

TEST(EnergyModel, ConfigurationReachesTheModel) {
  Config config({EnergyModel::parameters()});
  config.apply_override("power.bus.beats_pj=7.5");
  config.apply_override("power.bus.static_mw=2");
  const UnitEnergy e = EnergyModel::from_config(config).energy(UnitActivity{"bus", {{"beats", 2}}}, 1.0);
  EXPECT_DOUBLE_EQ(e.event_joules.at("beats"), 15e-12);
  EXPECT_DOUBLE_EQ(e.static_joules, 2e-3);
}

// The figures taken straight from docs/spec/calibration.md: idling on NOPs
// at 192 MHz draws 43.5 mA x 1.2 V, leakage 3 mA x 1.2 V.
TEST(EnergyModel, HostIdleAndLeakageDefaultsAreTheBoardFigures) {
  const UnitEnergy idle = EnergyModel::defaults().energy(UnitActivity{"host", {{"idle_cycles", 192e6}}}, 1.0);
  EXPECT_NEAR(idle.total_joules(), 43.5e-3 * 1.2, 1e-9);
  EXPECT_NEAR(idle.static_joules, 3e-3 * 1.2, 1e-12);
}

}  // namespace
