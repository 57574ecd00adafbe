// System tests of soc_sim --platform cluster (tlm/cluster, the sort-middle
// node program sw_driver/cluster_node): the frame does not depend on the
// number of nodes, the topology, the buffer depth or the network's timing
// (the split covers every pixel once, the termination protocol waits for
// every trapezoid), the statistics have their sections, and bad input is
// refused naming the key.
//
// Usage: test_soc_sim_cluster <path to soc_sim> [GoogleTest options]
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "fixtures/soc_sim_test.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tessera::test::contains;
using tessera::test::describe;
using tessera::test::SimResult;

constexpr int EXIT_USAGE = 2;

class SocSimCluster : public tessera::test::SocSimTest {
 protected:
  // A small random scene: 2,000 triangles of 12 pixels on 128 x 128.
  std::vector<std::string> scene(const std::string& out, unsigned nodes) const {
    return {"--platform", "cluster",
            "--frames",   "2",
            "--out",      out,
            "--set",      "cluster.nodes=" + std::to_string(nodes),
            "--set",      "cluster.triangles=2000",
            "--set",      "cluster.triangle_pixels=12",
            "--set",      "cluster.width=128",
            "--set",      "cluster.height=128"};
  }
  json stats(const std::string& out) const {
    std::ifstream in(m_dir / out / "stats.json");
    return json::parse(in, nullptr, false);
  }
};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  for (const std::string& arg : more) {
    args.push_back("--set");
    args.push_back(arg);
  }
  return args;
}

TEST_F(SocSimCluster, OneNodeSixtyFourAndTheMostDrawTheSameFrames) {
  const SimResult one = run(scene("p1", 1));
  ASSERT_EQ(one.status, 0) << describe(one);
  const SimResult many = run(scene("p64", 64));
  ASSERT_EQ(many.status, 0) << describe(many);
  // 128 nodes on 128 rows: a stripe of one row each (in 5 MiB of memory a
  // node, the program's 4 MiB and room for the stripe and the triangles,
  // so that the run stays small).
  const SimResult most = run(with(scene("p128", 128), {"cluster.node_memory_kib=5120"}));
  ASSERT_EQ(most.status, 0) << describe(most);
  for (unsigned f = 0; f < 2; ++f) {
    SCOPED_TRACE("frame " + std::to_string(f));
    ASSERT_FALSE(frame("p1", f).empty());
    EXPECT_EQ(frame("p1", f), frame("p64", f));
    EXPECT_EQ(frame("p1", f), frame("p128", f));
  }
  // Something was drawn: the PNG of an empty frame is far smaller.
  EXPECT_GT(frame("p1", 0).size(), 4000u);
}

TEST_F(SocSimCluster, TheFrameSurvivesAnyTopologyDepthAndRandomisedNetworkTiming) {
  ASSERT_EQ(run(scene("reference", 1)).status, 0);
  const std::string reference = frame("reference", 1);
  std::mt19937 random(20261202);
  const char* topologies[] = {"hypercube", "mesh", "ring", "crossbar"};
  for (unsigned trial = 0; trial < 6; ++trial) {
    const unsigned nodes = 1u << (1 + random() % 5);  // 2 .. 32, a power of two for the hypercube
    const std::string out = "trial" + std::to_string(trial);
    const std::vector<std::string> settings = {std::string("network.topology=") + topologies[random() % 4],
                                               "cluster.buffer_depth=" + std::to_string(1 + random() % 40),
                                               "network.hop_latency_ns=" + std::to_string(random() % 20000),
                                               "network.message_latency_ns=" + std::to_string(random() % 100000),
                                               "network.link_mb_per_s=" + std::to_string(1 + random() % 400)};
    SCOPED_TRACE(out + " nodes " + std::to_string(nodes) + ": " + settings[0] + " " + settings[1] + " " + settings[2] +
                 " " + settings[3] + " " + settings[4]);
    const SimResult result = run(with(scene(out, nodes), settings));
    ASSERT_EQ(result.status, 0) << describe(result);
    EXPECT_EQ(frame(out, 1), reference);
  }
}

TEST_F(SocSimCluster, TheIssDrawsWhatTheHostCompiledModelDraws) {
  // Two nodes of the cross-compiled program (tessera_cluster_node.elf) on
  // the ISS, a small scene: the same frames, and a frame time within the
  // host-compiled model's calibration of it (the sort_middle_* rows were
  // measured on such runs: sw_driver/costs/README.md).
  const std::vector<std::string> small = {"--set", "cluster.triangles=600", "--set", "cluster.nodes=2"};
  std::vector<std::string> native = scene("native", 2), iss = scene("iss", 2);
  native.insert(native.end(), small.begin(), small.end());
  iss.insert(iss.end(), small.begin(), small.end());
  iss.insert(iss.end(), {"--set", "host.model=iss"});
  const SimResult on_native = run(native);
  ASSERT_EQ(on_native.status, 0) << describe(on_native);
  const SimResult on_iss = run(iss);
  ASSERT_EQ(on_iss.status, 0) << describe(on_iss);
  for (unsigned f = 0; f < 2; ++f) EXPECT_EQ(frame("native", f), frame("iss", f)) << "frame " << f;
  const double native_ns = stats("native")["stats"]["frames"][1]["render_ns"].get<double>();
  const double iss_ns = stats("iss")["stats"]["frames"][1]["render_ns"].get<double>();
  EXPECT_NEAR(native_ns / iss_ns, 1.0, 0.25) << native_ns << " ns natively, " << iss_ns << " ns on the ISS";
}

TEST_F(SocSimCluster, SixteenIssNodesDrawWhatOneNativeNodeDraws) {
  // Sixteen copies of the ARM program, each its own ISS, trading trapezoids:
  // the frames are the host-compiled single node's.
  ASSERT_EQ(run(with(scene("one", 1), {"cluster.triangles=600"})).status, 0);
  const SimResult iss = run(with(scene("iss16", 16), {"cluster.triangles=600", "host.model=iss"}));
  ASSERT_EQ(iss.status, 0) << describe(iss);
  for (unsigned f = 0; f < 2; ++f) EXPECT_EQ(frame("one", f), frame("iss16", f)) << "frame " << f;
  EXPECT_EQ(stats("iss16")["stats"]["nodes"].size(), 16u);
}

TEST_F(SocSimCluster, StatisticsHaveTheNodesTheNetworkAndTheFrames) {
  const SimResult result = run(scene("out", 4));
  ASSERT_EQ(result.status, 0) << describe(result);
  const json document = stats("out");
  ASSERT_FALSE(document.is_discarded());
  const json& s = document["stats"];
  EXPECT_EQ(s["platform"], "cluster");
  ASSERT_EQ(s["nodes"].size(), 4u);
  EXPECT_EQ(s["frames"].size(), 2u);
  uint64_t sent = 0, received = 0, made = 0, drawn = 0;
  for (const json& node : s["nodes"]) {
    ASSERT_EQ(node["frames"].size(), 2u);
    for (const json& f : node["frames"]) {
      sent += f["trapezoids_sent"].get<uint64_t>();
      received += f["trapezoids_received"].get<uint64_t>();
      made += f["trapezoids_made"].get<uint64_t>();
      drawn += f["trapezoids_drawn"].get<uint64_t>();
    }
  }
  // Every trapezoid sent is received; every one made is drawn by its owner
  // (sent, or its maker's own).
  EXPECT_GT(sent, 0u);
  EXPECT_EQ(sent, received);
  EXPECT_EQ(made, drawn);
  EXPECT_GT(s["network"]["messages"].get<uint64_t>(), 0u);
  EXPECT_GT(s["energy"]["total_j"].get<double>(), 0.0);
  // Each frame's energy is its nodes' and its network's; the frames' lie
  // within the run's (which has the gathering after the last frame too).
  double frames_nodes = 0, frames_network = 0;
  for (const json& f : s["frames"]) {
    const double nodes = f["energy"]["units"]["nodes"]["total_j"].get<double>();
    const double network = f["energy"]["units"]["network"]["total_j"].get<double>();
    EXPECT_GT(nodes, 0.0);
    EXPECT_GT(network, 0.0);
    EXPECT_DOUBLE_EQ(f["energy"]["total_j"].get<double>(), nodes + network);
    frames_nodes += nodes, frames_network += network;
  }
  EXPECT_LE(frames_nodes, s["energy"]["nodes_j"].get<double>());
  EXPECT_LE(frames_network, s["energy"]["network_j"].get<double>());
  EXPECT_TRUE(contains(result.out, "busiest node")) << result.out;
}

TEST_F(SocSimCluster, BadInputIsRefusedNamingTheKey) {
  struct Case {
    std::vector<std::string> settings;
    std::string names;
  };
  const Case cases[] = {
      {{"cluster.nodes=129"}, "cluster.nodes"},
      {{"cluster.nodes=0"}, "cluster.nodes"},
      {{"cluster.nodes=12"}, "hypercube"},
      {{"cluster.buffer_depth=0"}, "cluster.buffer_depth"},
      {{"cluster.buffer_depth=many"}, "cluster.buffer_depth"},
      {{"cluster.node_memory_kib=4096", "cluster.nodes=1"}, "cluster.node_memory_kib"},
      {{"network.link_mb_per_s=0"}, "network.link_mb_per_s"},
      {{"network.hop_latency_ns=-1"}, "network.hop_latency_ns"},
      {{"mem.size_mib=32"}, "cluster.node_memory_kib"},
      {{"cluster.nodes=64", "cluster.height=32"}, "cluster.height"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.settings.front());
    std::vector<std::string> args = {"--platform", "cluster", "--out", "bad"};
    const SimResult result = run(with(args, c.settings));
    EXPECT_EQ(result.status, EXIT_USAGE) << describe(result);
    EXPECT_TRUE(contains(result.err, c.names)) << result.err;
  }
  // A depth whose buffers cannot fit the memory: refused by the program.
  const SimResult deep = run(with(scene("deep", 128), {"cluster.buffer_depth=60000"}));
  EXPECT_EQ(deep.status, EXIT_USAGE) << describe(deep);
  EXPECT_TRUE(contains(deep.err, "cluster.buffer_depth")) << deep.err;
  // GDB debugs one program; the cluster runs one a node.
  const SimResult gdb = run({"--platform", "cluster", "--set", "host.model=iss", "--gdb", "0", "--out", "gdb"});
  EXPECT_EQ(gdb.status, EXIT_USAGE) << describe(gdb);
  EXPECT_TRUE(contains(gdb.err, "--gdb")) << gdb.err;
  // A scene the cluster does not draw.
  const SimResult scene_name = run({"--platform", "cluster", "--scene", "cubes", "--out", "cubes"});
  EXPECT_EQ(scene_name.status, EXIT_USAGE) << describe(scene_name);
  EXPECT_TRUE(contains(scene_name.err, "cluster.scene")) << scene_name.err;
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
