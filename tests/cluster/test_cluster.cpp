// TLM tests of the cluster platform's assembly (tlm/cluster): four native
// nodes on a hypercube, each running a small program of its own through
// the node's memory map (the network interface's driver, the host link),
// not the sort-middle program. Node 0 sends a message to every other node,
// each answers; every node paints its stripe in its own colour and tells
// the platform where it is; node 0 reports the frame complete. Then: the
// messages arrived with their payloads, the gathered frame has each
// stripe's rows in place at the time of the report, the statistics name
// every node's blocks, and the parameter group's checks name their keys.
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cluster/cluster.h"
#include "cluster/host_link_regs.h"
#include "cluster/node_memory_map.h"
#include "cluster/stripe_layout.h"
#include "device/network_driver.h"
#include "soc/soc.h"

using namespace tessera;

namespace {

constexpr unsigned NODES = 4, WIDTH = 8, HEIGHT = 10;
constexpr uint32_t RINGS = 0x100000, PAYLOAD = 0x110000, STRIPE = 0x200000;

struct Observed {
  std::vector<uint32_t> received_words;  // per node: the first payload word it received
  std::vector<unsigned> received_from;
  std::vector<Frame> frames;
  double report_seconds = 0;
  bool done = false;
  int exit_code = -1;
};
Observed g_observed;

Config cluster_config() {
  std::vector<ParamGroup> groups = Soc::parameter_groups();
  for (ParamGroup& group : Cluster::parameter_groups()) groups.push_back(std::move(group));
  Config config(groups);
  config.set("cluster.nodes", NODES, "test");
  config.set("cluster.width", WIDTH, "test");
  config.set("cluster.height", HEIGHT, "test");
  config.set("cluster.node_memory_kib", 8192, "test");
  config.validate();
  return config;
}

uint32_t colour_of(unsigned node) {
  return 0xFF000000u | (node + 1) * 0x00102030u;
}

int node_program(HostApi& host) {
  NetworkDriver net(host);
  const unsigned id = net.id();
  net.start({RINGS, 8, RINGS + 0x1000, 4, 64});
  // The stripe, in the node's colour.
  const unsigned rows = stripes::rows(id, HEIGHT, NODES);
  for (unsigned i = 0; i < rows * WIDTH; ++i) host.write32(STRIPE + 4 * i, colour_of(id));
  host.write32(node_memory_map::host_link.base + host_link_regs::STRIPE_ADDRESS, STRIPE);
  NetworkDriver::Message message;
  if (id == 0) {
    for (unsigned j = 1; j < NODES; ++j) {
      host.write32(PAYLOAD + 4 * j, 0xC0DE0000u + j);
      net.send(j, PAYLOAD + 4 * j, 4, 7);
    }
    for (unsigned answers = 0; answers < NODES - 1;) {
      if (!net.peek(message)) {
        net.wait();
        continue;
      }
      g_observed.received_words[0] += host.read32(message.payload);
      net.release();
      ++answers;
    }
    g_observed.report_seconds = host.now_seconds();
    host.write32(node_memory_map::host_link.base + host_link_regs::FRAME_DONE, 0);
  } else {
    while (!net.peek(message)) net.wait();
    g_observed.received_words[id] = host.read32(message.payload);
    g_observed.received_from[id] = message.source;
    net.release();
    host.write32(PAYLOAD, 0x100u * id);
    net.wait_sent(net.send(0, PAYLOAD, 4, 8));
  }
  return 0;
}

TEST(Cluster, EveryNodeHearsNodeZeroAndAnswers) {
  ASSERT_TRUE(g_observed.done);
  EXPECT_EQ(g_observed.exit_code, 0);
  for (unsigned j = 1; j < NODES; ++j) {
    EXPECT_EQ(g_observed.received_words[j], 0xC0DE0000u + j) << j;
    EXPECT_EQ(g_observed.received_from[j], 0u) << j;
  }
  EXPECT_EQ(g_observed.received_words[0], 0x100u + 0x200u + 0x300u);
}

TEST(Cluster, TheFrameIsGatheredFromTheStripesAtTheReport) {
  ASSERT_EQ(g_observed.frames.size(), 1u);
  const Frame& frame = g_observed.frames.front();
  EXPECT_EQ(frame.width, WIDTH);
  EXPECT_EQ(frame.height, HEIGHT);
  EXPECT_NEAR(frame.time_seconds, g_observed.report_seconds, 1e-7);
  // Rows [floor(s H / p), floor((s + 1) H / p)): 0-1, 2-4, 5-6, 7-9.
  const unsigned owner[HEIGHT] = {0, 0, 1, 1, 1, 2, 2, 3, 3, 3};
  for (unsigned y = 0; y < HEIGHT; ++y)
    for (unsigned x = 0; x < WIDTH; ++x) {
      const uint8_t* pixel = &frame.rgba[(y * WIDTH + x) * 4];
      const uint32_t word = pixel[0] | pixel[1] << 8 | pixel[2] << 16 | uint32_t{pixel[3]} << 24;
      EXPECT_EQ(word, colour_of(owner[y])) << "row " << y;
    }
}

// What configuration each case was refused with ("" if accepted), worked
// out in sc_main before the simulation: an exception thrown on sc_main's
// stack after the kernel has switched to its processes and back confuses
// the address sanitizer's view of the stack.
struct Refusals {
  std::string too_many_nodes, fewer_rows_than_nodes, zero_depth, small_memory, soc_memory, accepted;
  bool depth_auto_is_0 = false, depth_65535 = false, depth_65536_refused = false, depth_negative_refused = false;
};
Refusals g_refusals;

std::string refusal(const std::vector<std::pair<std::string, nlohmann::json>>& settings) {
  std::vector<ParamGroup> groups = Soc::parameter_groups();
  for (ParamGroup& group : Cluster::parameter_groups()) groups.push_back(std::move(group));
  try {
    Config config(groups);
    for (const auto& [key, value] : settings) config.set(key, value, "test");
    config.validate();
    (void)ClusterParams::from_config(config);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

bool refused_depth(const std::string& text) {
  try {
    (void)parse_buffer_depth(text);
  } catch (const ConfigError&) {
    return true;
  }
  return false;
}

void work_out_refusals() {
  Refusals& r = g_refusals;
  r.too_many_nodes = refusal({{"cluster.nodes", 129}});
  r.fewer_rows_than_nodes = refusal({{"cluster.nodes", 64}, {"cluster.height", 32}});
  r.zero_depth = refusal({{"cluster.buffer_depth", "0"}});
  r.small_memory = refusal({{"cluster.node_memory_kib", 4096}});
  r.soc_memory = refusal({{"mem.size_mib", 32}});
  r.accepted = refusal({{"cluster.buffer_depth", "12"}});
  r.depth_auto_is_0 = !refused_depth("auto") && parse_buffer_depth("auto") == 0;
  r.depth_65535 = !refused_depth("65535") && parse_buffer_depth("65535") == 65535;
  r.depth_65536_refused = refused_depth("65536");
  r.depth_negative_refused = refused_depth("-3");
}

TEST(Cluster, ParameterChecksNameTheirKeys) {
  const Refusals& r = g_refusals;
  EXPECT_NE(r.too_many_nodes.find("cluster.nodes"), std::string::npos) << r.too_many_nodes;
  EXPECT_NE(r.fewer_rows_than_nodes.find("cluster.height"), std::string::npos) << r.fewer_rows_than_nodes;
  EXPECT_NE(r.zero_depth.find("cluster.buffer_depth"), std::string::npos) << r.zero_depth;
  EXPECT_NE(r.small_memory.find("cluster.node_memory_kib"), std::string::npos) << r.small_memory;
  EXPECT_NE(r.soc_memory.find("cluster.node_memory_kib"), std::string::npos) << r.soc_memory;
  EXPECT_EQ(r.accepted, "");
  EXPECT_TRUE(r.depth_auto_is_0);
  EXPECT_TRUE(r.depth_65535);
  EXPECT_TRUE(r.depth_65536_refused);
  EXPECT_TRUE(r.depth_negative_refused);
}

TEST(Cluster, TheStripeRuleGivesEveryRowToOneNode) {
  for (unsigned height = 1; height <= 64; ++height)
    for (unsigned nodes = 1; nodes <= height && nodes <= 128; ++nodes) {
      unsigned covered = 0;
      for (unsigned s = 0; s < nodes; ++s) {
        EXPECT_GE(stripes::rows(s, height, nodes), 1u);
        for (unsigned y = stripes::first_row(s, height, nodes); y < stripes::first_row(s + 1, height, nodes); ++y) {
          EXPECT_EQ(stripes::owner_of_row(y, height, nodes), s);
          ++covered;
        }
      }
      EXPECT_EQ(covered, height);
    }
}

}  // namespace

int sc_main(int argc, char* argv[]) {
  ::testing::InitGoogleTest(&argc, argv);
  work_out_refusals();
  g_observed.received_words.assign(NODES, 0);
  g_observed.received_from.assign(NODES, ~0u);
  const Config config = cluster_config();
  Cluster cluster("cluster", config);
  cluster.set_programs([](unsigned) { return Host::Program(node_program); });
  cluster.on_frame([](const Frame& frame) { g_observed.frames.push_back(frame); });
  sc_core::sc_start(sc_core::sc_time(1, sc_core::SC_SEC));
  g_observed.done = cluster.done();
  g_observed.exit_code = cluster.exit_code();
  return RUN_ALL_TESTS();
}
