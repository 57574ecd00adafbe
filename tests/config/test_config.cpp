// Tests of tessera::Config: defaults, merging JSON documents and key=value
// overrides, and the errors for every kind of bad input. An error must name
// the key (or file) and what was expected, so the tests look for those words
// in the message rather than for a copy of its whole text. The parameters are
// a table of this test's own, with one of each type and a combination check,
// shaped like the blocks' (the SoC's real table is tested in tests/soc/).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "config/config.h"
#include "fixtures/scratch_folder_test.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tessera::Config;
using tessera::ConfigError;
using tessera::ParamGroup;
using tessera::ParamType;

// Two groups as blocks declare them: the second checks a combination.
std::vector<ParamGroup> groups() {
  namespace param = tessera::param;
  ParamGroup sim{"sim",
                 {param::text("sim.app", "teapot", "application to run"),
                  param::integer("sim.frames", 3, 1, 100000, "frames", "frames to draw")},
                 {}};
  ParamGroup display{
      "display",
      {param::integer("display.width", 320, 16, 2048, "pixels", "visible pixels per line"),
       param::integer("display.height", 240, 16, 2048, "lines", "visible lines"),
       param::choice("display.format", "rgb565", {"rgb565", "rgba8888"}, "frame-buffer pixel format"),
       param::boolean("display.dma", false, "display DMA"),
       param::real("display.refresh_hz", 60.0, 1, 240, "Hz", "refresh rate"),
       param::real("host.clock_mhz", 192.0, 1, 2000, "MHz", "core clock"),
       param::choice("bus.arbitration", "fixed_priority", {"fixed_priority", "round_robin"}, "arbitration"),
       param::real("bus.clock_mhz", 96.0, 1, 2000, "MHz", "bus clock"),
       param::integer("bus.width_bits", 32, 32, 128, "bits", "data width"),
       param::integer("host.cycles.alu", 1, 0, 100, "cycles", "data-processing instruction"),
       param::integer("host.cycles.mul", 3, 0, 100, "cycles", "multiply"),
       param::integer("host.dcache.size_bytes", 8192, 0, 1048576, "bytes", "data cache size"),
       param::integer("mem.size_mib", 16, 1, 256, "MiB", "system memory size")},
      [](const Config& config) {
        if (config.get_uint("display.width") * config.get_uint("display.height") > 1000000)
          throw ConfigError("configuration: impossible combination: display.width x display.height above 1000000");
      }};
  return {sim, display};
}

Config make_config() {
  return Config(groups());
}

std::vector<tessera::ParamSpec> all_specs() {
  return make_config().specs();
}

// The message of the ConfigError `action` throws; fails the test if it
// throws nothing or something else.
std::string config_error(const std::function<void()>& action) {
  try {
    action();
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected ConfigError, got another exception: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected ConfigError, nothing was thrown";
  return {};
}

#define EXPECT_MENTIONS(message, text) \
  EXPECT_NE((message).find(text), std::string::npos) << "message: " << (message) << "\nlacks: " << (text)

// A file in a fresh temporary folder, removed with the fixture.
class ConfigFiles : public tessera::test::ScratchFolderTest {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = m_dir / name;
    std::ofstream(path) << text;
    return path.string();
  }
};

TEST(ConfigDefaults, EveryParameterHasItsDefaultWithItsType) {
  const Config config = make_config();
  for (const auto& spec : all_specs()) {
    SCOPED_TRACE(spec.key);
    switch (spec.type) {
      case ParamType::boolean:
        ASSERT_TRUE(spec.default_value.is_boolean());
        EXPECT_EQ(config.get_bool(spec.key), spec.default_value.get<bool>());
        break;
      case ParamType::integer:
        ASSERT_TRUE(spec.default_value.is_number_integer());
        EXPECT_EQ(config.get_int(spec.key), spec.default_value.get<int64_t>());
        EXPECT_GE(config.get_int(spec.key), spec.min);
        EXPECT_LE(config.get_int(spec.key), spec.max);
        break;
      case ParamType::real:
        ASSERT_TRUE(spec.default_value.is_number());
        EXPECT_DOUBLE_EQ(config.get_real(spec.key), spec.default_value.get<double>());
        EXPECT_GE(config.get_real(spec.key), spec.min);
        EXPECT_LE(config.get_real(spec.key), spec.max);
        break;
      case ParamType::string:
        ASSERT_TRUE(spec.default_value.is_string());
        EXPECT_EQ(config.get_string(spec.key), spec.default_value.get<std::string>());
        break;
      case ParamType::choice: {
        ASSERT_TRUE(spec.default_value.is_string());
        const std::string value = config.get_string(spec.key);
        EXPECT_NE(std::find(spec.choices.begin(), spec.choices.end(), value), spec.choices.end());
        break;
      }
    }
  }
}

TEST(ConfigDefaults, ADuplicateKeyIsAProgrammingErrorNamingBothOwners) {
  std::vector<ParamGroup> twice = groups();
  twice.push_back({"other", {tessera::param::integer("sim.frames", 1, 1, 2, "", "again")}, {}});
  try {
    Config config(twice);
    ADD_FAILURE() << "a key declared twice was accepted";
  } catch (const std::logic_error& e) {
    EXPECT_MENTIONS(std::string(e.what()), "sim.frames");
    EXPECT_MENTIONS(std::string(e.what()), "sim");
    EXPECT_MENTIONS(std::string(e.what()), "other");
  }
}

TEST(ConfigValidate, EveryGroupsCheckRunsAndNamesTheKeys) {
  Config config = make_config();
  EXPECT_NO_THROW(config.validate());
  config.apply_override("display.width=2048");
  config.apply_override("display.height=2048");  // each value is legal on its own
  const std::string message = config_error([&] { config.validate(); });
  EXPECT_MENTIONS(message, "impossible combination");
  EXPECT_MENTIONS(message, "display.width");
  EXPECT_MENTIONS(message, "display.height");
}

TEST(ConfigDefaults, KeysAreUniqueAndDotted) {
  std::set<std::string> keys;
  for (const auto& spec : all_specs()) {
    EXPECT_TRUE(keys.insert(spec.key).second) << "duplicate key " << spec.key;
    EXPECT_NE(spec.key.find('.'), std::string::npos) << spec.key;
    EXPECT_FALSE(spec.description.empty()) << spec.key;
  }
}

TEST(ConfigDefaults, ReadingAsTheWrongTypeIsAProgrammingError) {
  const Config config = make_config();
  EXPECT_THROW(config.get_bool("display.width"), std::logic_error);
  EXPECT_THROW(config.get_int("display.dma"), std::logic_error);
  // An unknown key read by code is reported as a ConfigError naming it.
  EXPECT_MENTIONS(config_error([&] { config.get_int("display.widht"); }), "display.widht");
}

TEST(ConfigMerge, NestedObjectsAndDottedKeysBothMerge) {
  Config config = make_config();
  config.merge_json(json::parse(R"({"bus": {"arbitration": "round_robin", "clock_mhz": 133.0},
                                    "display.width": 640,
                                    "host": {"cycles.mul": 5, "dcache": {"size_bytes": 4096}}})"),
                    "test");
  EXPECT_EQ(config.get_string("bus.arbitration"), "round_robin");
  EXPECT_DOUBLE_EQ(config.get_real("bus.clock_mhz"), 133.0);
  EXPECT_EQ(config.get_int("display.width"), 640);
  EXPECT_EQ(config.get_int("host.cycles.mul"), 5);
  EXPECT_EQ(config.get_int("host.dcache.size_bytes"), 4096);
  // Untouched parameters keep their defaults.
  EXPECT_EQ(config.get_int("display.height"), 240);
}

TEST(ConfigMerge, LaterDocumentsOverrideEarlierOnes) {
  Config config = make_config();
  config.merge_json({{"display", {{"width", 640}}}}, "first");
  config.merge_json({{"display.width", 800}}, "second");
  EXPECT_EQ(config.get_int("display.width"), 800);
}

TEST(ConfigMerge, IntegerIsAcceptedForARealParameter) {
  Config config = make_config();
  config.set("host.clock_mhz", 200, "test");
  EXPECT_DOUBLE_EQ(config.get_real("host.clock_mhz"), 200.0);
}

TEST(ConfigErrors, UnknownKeyIsNamedWithTheNearestKnownKey) {
  Config config = make_config();
  const std::string message = config_error([&] {
    config.merge_json({{"bus", {{"arbitraton", "round_robin"}}}}, "my.json");
  });
  EXPECT_MENTIONS(message, "bus.arbitraton");
  EXPECT_MENTIONS(message, "did you mean 'bus.arbitration'");
  EXPECT_MENTIONS(message, "my.json");
}

TEST(ConfigErrors, UnknownKeyFarFromAnyKnownKeyGetsNoSuggestion) {
  Config config = make_config();
  const std::string message = config_error([&] { config.set("frobnicator.level", 3, "test"); });
  EXPECT_MENTIONS(message, "frobnicator.level");
  EXPECT_MENTIONS(message, "unknown key");
  EXPECT_EQ(message.find("did you mean"), std::string::npos) << message;
}

TEST(ConfigErrors, WrongTypeNamesTheKeyAndTheExpectedType) {
  struct Case {
    const char* key;
    json value;
    const char* expected;
  };
  const Case cases[] = {
      {"sim.frames", "many", "integer"},          // string for integer
      {"sim.frames", 2.5, "integer"},             // real for integer
      {"sim.frames", true, "integer"},            // boolean for integer
      {"display.dma", 1, "boolean"},              // number for boolean
      {"display.dma", "true", "boolean"},         // string for boolean
      {"host.clock_mhz", "fast", "number"},       // string for real
      {"sim.app", 7, "string"},                   // number for string
      {"bus.arbitration", false, "round_robin"},  // boolean for choice: lists the choices
      {"display.width", json::array({1, 2}), "integer"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(std::string(c.key) + " = " + c.value.dump());
    Config config = make_config();
    const std::string message = config_error([&] { config.set(c.key, c.value, "test"); });
    EXPECT_MENTIONS(message, c.key);
    EXPECT_MENTIONS(message, c.expected);
  }
}

TEST(ConfigErrors, OutOfRangeNamesTheKeyAndTheRange) {
  Config config = make_config();
  std::string message = config_error([&] { config.set("mem.size_mib", 100000, "test"); });
  EXPECT_MENTIONS(message, "mem.size_mib");
  EXPECT_MENTIONS(message, "256");
  EXPECT_MENTIONS(message, "100000");

  message = config_error([&] { config.set("sim.frames", 0, "test"); });
  EXPECT_MENTIONS(message, "sim.frames");
  EXPECT_MENTIONS(message, "[1, ");

  message = config_error([&] { config.set("sim.quantum_ns", -1, "test"); });
  EXPECT_MENTIONS(message, "sim.quantum_ns");

  message = config_error([&] { config.set("host.clock_mhz", 0.5, "test"); });
  EXPECT_MENTIONS(message, "host.clock_mhz");
  EXPECT_MENTIONS(message, "2000");

  message = config_error([&] { config.set("display.refresh_hz", 1e6, "test"); });
  EXPECT_MENTIONS(message, "display.refresh_hz");
  EXPECT_MENTIONS(message, "240");

  // Nothing was stored by the failed attempts.
  EXPECT_EQ(config.get_int("mem.size_mib"), make_config().get_int("mem.size_mib"));
  EXPECT_DOUBLE_EQ(config.get_real("host.clock_mhz"), make_config().get_real("host.clock_mhz"));
}

TEST(ConfigErrors, BadChoiceListsTheChoices) {
  Config config = make_config();
  const std::string message = config_error([&] { config.set("bus.arbitration", "lottery", "test"); });
  EXPECT_MENTIONS(message, "bus.arbitration");
  EXPECT_MENTIONS(message, "lottery");
  EXPECT_MENTIONS(message, "fixed_priority");
  EXPECT_MENTIONS(message, "round_robin");
}

TEST(ConfigOverride, ParsesEachType) {
  Config config = make_config();
  config.apply_override("display.dma=true");
  EXPECT_TRUE(config.get_bool("display.dma"));
  config.apply_override("display.dma=false");
  EXPECT_FALSE(config.get_bool("display.dma"));
  config.apply_override("display.dma=1");
  EXPECT_TRUE(config.get_bool("display.dma"));
  config.apply_override("display.dma=0");
  EXPECT_FALSE(config.get_bool("display.dma"));

  config.apply_override("sim.frames=7");
  EXPECT_EQ(config.get_int("sim.frames"), 7);
  config.apply_override("sim.frames=0x10");
  EXPECT_EQ(config.get_int("sim.frames"), 16);

  config.apply_override("host.clock_mhz=200.5");
  EXPECT_DOUBLE_EQ(config.get_real("host.clock_mhz"), 200.5);
  config.apply_override("host.clock_mhz=1e2");
  EXPECT_DOUBLE_EQ(config.get_real("host.clock_mhz"), 100.0);
  config.apply_override("host.clock_mhz=150");
  EXPECT_DOUBLE_EQ(config.get_real("host.clock_mhz"), 150.0);

  config.apply_override("bus.arbitration=round_robin");
  EXPECT_EQ(config.get_string("bus.arbitration"), "round_robin");

  config.apply_override("sim.app=/opt/apps/libdemo.so");
  EXPECT_EQ(config.get_string("sim.app"), "/opt/apps/libdemo.so");
  // Only the first '=' separates key from value.
  config.apply_override("sim.app=a=b");
  EXPECT_EQ(config.get_string("sim.app"), "a=b");
}

TEST(ConfigOverride, GarbageValuesNameTheKey) {
  const char* garbage[] = {"display.dma=maybe",      "display.dma=",        "sim.frames=many",
                           "sim.frames=12abc",       "sim.frames=",         "sim.frames=3.5",
                           "host.clock_mhz=fast",    "host.clock_mhz=1.5x", "sim.frames=99999999999999999999999",
                           "bus.arbitration=lottery"};
  for (const char* assignment : garbage) {
    SCOPED_TRACE(assignment);
    Config config = make_config();
    const std::string message = config_error([&] { config.apply_override(assignment); });
    const std::string text(assignment);
    EXPECT_MENTIONS(message, text.substr(0, text.find('=')));
    EXPECT_MENTIONS(message, "expects");
  }
}

TEST(ConfigOverride, OutOfRangeOverrideIsRejected) {
  Config config = make_config();
  const std::string message = config_error([&] { config.apply_override("mem.size_mib=100000"); });
  EXPECT_MENTIONS(message, "mem.size_mib");
  EXPECT_MENTIONS(message, "256");
}

TEST(ConfigOverride, UnknownKeySuggestsTheNearMiss) {
  Config config = make_config();
  const std::string message = config_error([&] { config.apply_override("bus.arbitraton=round_robin"); });
  EXPECT_MENTIONS(message, "bus.arbitraton");
  EXPECT_MENTIONS(message, "bus.arbitration");
}

TEST(ConfigOverride, AssignmentWithoutEqualsSignIsRejected) {
  Config config = make_config();
  std::string message = config_error([&] { config.apply_override("display.dma"); });
  EXPECT_MENTIONS(message, "display.dma");
  EXPECT_MENTIONS(message, "key=value");

  message = config_error([&] { config.apply_override("=5"); });
  EXPECT_MENTIONS(message, "key=value");
}

TEST_F(ConfigFiles, LoadsAFile) {
  Config config = make_config();
  config.load_file(write("good.json", R"({"display": {"width": 640, "height": 480}, "sim.frames": 2})"));
  EXPECT_EQ(config.get_int("display.width"), 640);
  EXPECT_EQ(config.get_int("display.height"), 480);
  EXPECT_EQ(config.get_int("sim.frames"), 2);
}

TEST_F(ConfigFiles, MissingFileIsNamed) {
  Config config = make_config();
  const std::string path = (m_dir / "does_not_exist.json").string();
  const std::string message = config_error([&] { config.load_file(path); });
  EXPECT_MENTIONS(message, path);
  EXPECT_MENTIONS(message, "No such file");
}

TEST_F(ConfigFiles, MalformedJsonIsNamedAsSuch) {
  Config config = make_config();
  const std::string path = write("broken.json", "{\"bus\": {\"arbitration\": \"round_robin\",\n");
  const std::string message = config_error([&] { config.load_file(path); });
  EXPECT_MENTIONS(message, "not valid JSON");
  EXPECT_MENTIONS(message, path);
}

TEST_F(ConfigFiles, TopLevelArrayIsRejected) {
  Config config = make_config();
  const std::string path = write("array.json", R"([{"display.width": 640}])");
  const std::string message = config_error([&] { config.load_file(path); });
  EXPECT_MENTIONS(message, path);
  EXPECT_MENTIONS(message, "object");
  EXPECT_EQ(config.get_int("display.width"), 320);
}

TEST_F(ConfigFiles, BadFileLeavesTheConfigurationUnchanged) {
  Config config = make_config();
  config.apply_override("display.height=480");
  const json before = config.to_json();
  // Valid entries come before and after the bad ones in the document.
  const char* bad_documents[] = {
      R"({"display": {"width": 640}, "bus.arbitration": "lottery", "sim": {"frames": 9}})",
      R"({"display": {"width": 640}, "bus": {"arbitraton": "round_robin"}, "sim": {"frames": 9}})",
      R"({"display": {"width": 640}, "mem.size_mib": 100000})",
  };
  for (const char* document : bad_documents) {
    SCOPED_TRACE(document);
    const std::string path = write("bad.json", document);
    const std::string message = config_error([&] { config.load_file(path); });
    EXPECT_MENTIONS(message, path);
    EXPECT_EQ(config.to_json(), before);
  }
  EXPECT_EQ(config.get_int("display.width"), 320);
  EXPECT_EQ(config.get_int("display.height"), 480);
}

// Issue 14: a file must not be able to knock the loader over. Nesting is
// refused past MAX_CONFIG_DEPTH (200 KB of nested arrays used to overflow the
// stack; 100000 nested objects took gigabytes), by the key where it happened.
TEST_F(ConfigFiles, DeepNestingIsRefusedByDepthNotByTheStack) {
  Config config = make_config();
  const std::size_t arrays = 100000;  // 200 KB
  const std::string path =
      write("arrays.json", "{\"sim.app\": " + std::string(arrays, '[') + std::string(arrays, ']') + "}");
  std::string message = config_error([&] { config.load_file(path); });
  EXPECT_MENTIONS(message, path);
  EXPECT_MENTIONS(message, "more than 32 deep");
  EXPECT_MENTIONS(message, "'sim.app[0][0]");

  std::string objects;
  for (int i = 0; i < 100000; ++i) objects += "{\"a\":";
  objects += "1" + std::string(100000, '}');
  message = config_error([&] { config.load_file(write("objects.json", objects)); });
  EXPECT_MENTIONS(message, "more than 32 deep (at 'a.a.a.");
  EXPECT_EQ(config.get_string("sim.app"), "teapot");
}

TEST_F(ConfigFiles, NestingUpToTheLimitIsParsed) {
  ASSERT_EQ(tessera::MAX_CONFIG_DEPTH, 32u);
  // 32 levels: the top-level object and 31 below it; the key is unknown, so
  // the error is about the key, not the depth.
  auto nested = [](std::size_t depth) {
    std::string text;
    for (std::size_t i = 0; i < depth; ++i) text += i == 0 ? "{" : "\"k\": {";
    text += "\"x\": 1" + std::string(depth, '}');
    return text;
  };
  Config config = make_config();
  std::string message = config_error([&] { config.load_file(write("deep.json", nested(32))); });
  EXPECT_MENTIONS(message, "unknown key 'k.k.k.");
  message = config_error([&] { config.load_file(write("deeper.json", nested(33))); });
  EXPECT_MENTIONS(message, "more than 32 deep");
}

TEST_F(ConfigFiles, FileSizeIsLimited) {
  ASSERT_EQ(tessera::MAX_CONFIG_FILE_BYTES, 1048576u);
  const std::string document = R"({"sim.frames": 7})";
  Config config = make_config();
  // Exactly at the limit (padded with white space) loads.
  config.load_file(write("full.json", document + std::string(tessera::MAX_CONFIG_FILE_BYTES - document.size(), ' ')));
  EXPECT_EQ(config.get_int("sim.frames"), 7);
  // One byte more does not.
  const std::string path =
      write("over.json", document + std::string(tessera::MAX_CONFIG_FILE_BYTES + 1 - document.size(), ' '));
  std::string message = config_error([&] { config.load_file(path); });
  EXPECT_MENTIONS(message, path);
  EXPECT_MENTIONS(message, "larger than the limit of 1048576 bytes");
  // A device without an end is read no further than the limit.
  if (fs::exists("/dev/zero")) {
    message = config_error([&] { config.load_file("/dev/zero"); });
    EXPECT_MENTIONS(message, "'/dev/zero' is larger than the limit");
  }
}

TEST_F(ConfigFiles, NumberBeyondADoubleNamesFileLineAndKey) {
  Config config = make_config();
  const std::string path = write("huge.json", "{\n  \"display\": {\n    \"refresh_hz\": 1e400\n  }\n}\n");
  std::string message = config_error([&] { config.load_file(path); });
  EXPECT_MENTIONS(message, "'" + path + "' line 3: 'display.refresh_hz' is 1e400, a number out of the range");
  message = config_error([&] { config.load_file(write("tiny.json", R"({"mem.size_mib": -2e999})")); });
  EXPECT_MENTIONS(message, "line 1: 'mem.size_mib' is -2e999");
  EXPECT_DOUBLE_EQ(config.get_real("display.refresh_hz"), 60.0);
  // The same number on the command line is refused by the key's type.
  message = config_error([&] { config.apply_override("display.refresh_hz=1e400"); });
  EXPECT_MENTIONS(message, "'display.refresh_hz' expects a number");
}

TEST_F(ConfigFiles, ObjectWhereAValueBelongsIsRefusedByKey) {
  Config config = make_config();
  for (const char* document :
       {R"({"display": {"width": {}}})", R"({"display": {"width": {"value": 640}}})", R"({"display.width": {}})"}) {
    SCOPED_TRACE(document);
    const std::string message = config_error([&] { config.load_file(write("object.json", document)); });
    EXPECT_MENTIONS(message, "'display.width' expects an integer in [16, 2048] (pixels), got {");
  }
  // An empty object under a name that is no group is an unknown key, not
  // nothing; an empty group is harmless.
  std::string message = config_error([&] { config.load_file(write("unknown.json", R"({"dispaly": {}})")); });
  EXPECT_MENTIONS(message, "unknown key 'dispaly'");
  config.load_file(write("empty_group.json", R"({"display": {}, "host": {"cycles": {}}})"));
  EXPECT_EQ(config.get_int("display.width"), 320);
}

TEST_F(ConfigFiles, KeyTwiceInOneObjectIsRefused) {
  Config config = make_config();
  const std::string path = write("twice.json", R"({"display": {"width": 640, "width": 800}})");
  const std::string message = config_error([&] { config.load_file(path); });
  EXPECT_MENTIONS(message, "'" + path + "' has 'display.width' twice");
  EXPECT_EQ(config.get_int("display.width"), 320);
}

TEST(ConfigOverrides, TextThatIsNotUtf8IsAnErrorNotALibraryException) {
  Config config = make_config();
  std::string message = config_error([&] { config.apply_override("sim.app=\xff\xfe"); });
  EXPECT_MENTIONS(message, "'sim.app' expects a string");
  EXPECT_MENTIONS(message, "not valid UTF-8");
  message = config_error([&] { config.apply_override("display.dma=\xff"); });
  EXPECT_MENTIONS(message, "'display.dma' expects a boolean");
  EXPECT_EQ(config.get_string("sim.app"), "teapot");
}

TEST(ConfigOverrides, LongWrongValueIsShortenedInTheMessage) {
  Config config = make_config();
  json many = json::array();
  for (int i = 0; i < 10000; ++i) many.push_back(i);
  const std::string message = config_error([&] { config.set("sim.frames", many, "test"); });
  EXPECT_MENTIONS(message, "'sim.frames' expects an integer");
  EXPECT_MENTIONS(message, "...");
  EXPECT_LT(message.size(), 300u);
}

TEST(ConfigJson, ToJsonRoundTripsThroughMergeJson) {
  Config changed = make_config();
  for (const char* assignment : {"bus.arbitration=round_robin", "display.dma=true", "display.format=rgba8888",
                                 "host.clock_mhz=166.5", "sim.frames=12", "sim.app=calib_add"})
    changed.apply_override(assignment);
  const json document = changed.to_json();
  // Nested objects, one level per dot.
  EXPECT_EQ(document.at("bus").at("arbitration"), "round_robin");
  EXPECT_EQ(document.at("host").at("cycles").at("alu"), changed.get_int("host.cycles.alu"));

  Config copy = make_config();
  copy.merge_json(document, "round trip");
  EXPECT_EQ(copy.to_json(), document);
  EXPECT_EQ(copy.get_string("bus.arbitration"), "round_robin");
  EXPECT_TRUE(copy.get_bool("display.dma"));
  EXPECT_EQ(copy.get_string("display.format"), "rgba8888");
  EXPECT_DOUBLE_EQ(copy.get_real("host.clock_mhz"), 166.5);
  EXPECT_EQ(copy.get_int("sim.frames"), 12);
  EXPECT_EQ(copy.get_string("sim.app"), "calib_add");

  // And through text, as soc_sim --print-config output would be reloaded.
  Config reparsed = make_config();
  reparsed.merge_json(json::parse(document.dump(2)), "text");
  EXPECT_EQ(reparsed.to_json(), document);
}

TEST(ConfigJson, ReferenceMarkdownListsEveryKey) {
  const std::string reference = make_config().reference_markdown();
  EXPECT_EQ(reference.rfind("| key |", 0), 0u) << reference.substr(0, 80);
  size_t rows = 0;
  for (char c : reference) rows += c == '\n';
  EXPECT_EQ(rows, all_specs().size() + 2);  // header and separator
  for (const auto& spec : all_specs()) {
    EXPECT_MENTIONS(reference, "`" + spec.key + "`");
    EXPECT_MENTIONS(reference, spec.description);
  }
}

}  // namespace
