// The cluster network's core (tlm/network/core): routes and hop counts of
// each topology, a message's latency computed by hand, time proportional to
// size, contention on a shared link and none on disjoint links, gap filling
// for calls out of time order, in-order delivery per pair, statistics, and
// every bad parameter naming its key.
//
// Unless a test says otherwise: hop latency 20 ns, 200 MB/s links (5 ns a
// byte), 100 ns set-up, 8 header bytes; a 92-byte payload is 100 bytes on
// the wire, 500 ns on a link.
#include <gtest/gtest.h>

#include <bitset>
#include <string>
#include <vector>

#include "config/config.h"
#include "network/core/network_model.h"

using namespace tessera;
using namespace tessera::network;

namespace {

constexpr uint64_t NS = 1000;  // picoseconds

NetworkConfig config(Topology topology, unsigned nodes) {
  NetworkConfig c;
  c.topology = topology;
  c.nodes = nodes;
  c.hop_latency_ns = 20;
  c.link_mb_per_s = 200;
  c.message_latency_ns = 100;
  c.header_bytes = 8;
  return c;
}

// "a->b" of a link name as the pair (a, b); "x" (the crossbar) as -1.
std::pair<int, int> ends(const std::string& name) {
  const size_t arrow = name.find("->");
  const std::string a = name.substr(0, arrow), b = name.substr(arrow + 2);
  return {a == "x" ? -1 : std::stoi(a), b == "x" ? -1 : std::stoi(b)};
}

// The route's links join src to dst, each starting where the one before
// ended, on links that exist.
void expect_connected_route(const Routing& r, unsigned src, unsigned dst) {
  std::vector<unsigned> links;
  r.route(src, dst, links);
  int at = static_cast<int>(src);
  for (unsigned l : links) {
    ASSERT_TRUE(r.link_exists(l)) << src << "->" << dst << " uses " << r.link_name(l);
    const auto [from, to] = ends(r.link_name(l));
    EXPECT_EQ(from, at) << src << "->" << dst;
    at = to;
  }
  EXPECT_EQ(at, static_cast<int>(dst));
}

void expect_config_error(const NetworkConfig& c, const std::string& key) {
  try {
    NetworkModel model(c);
    ADD_FAILURE() << "no error for " << key;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(NetworkRouting, HypercubeHopsArePopcountAndRoutesCorrectTheLowestDimensionFirst) {
  const Routing r(Topology::hypercube, 16);
  for (unsigned s = 0; s < 16; ++s)
    for (unsigned d = 0; d < 16; ++d) {
      EXPECT_EQ(r.hops(s, d), std::bitset<8>(s ^ d).count());
      expect_connected_route(r, s, d);
    }
  std::vector<unsigned> links;
  r.route(5, 10, links);  // 0101 -> 1010: 5 -> 4 -> 6 -> 2 -> 10
  ASSERT_EQ(links.size(), 4u);
  EXPECT_EQ(r.link_name(links[0]), "5->4");
  EXPECT_EQ(r.link_name(links[1]), "4->6");
  EXPECT_EQ(r.link_name(links[2]), "6->2");
  EXPECT_EQ(r.link_name(links[3]), "2->10");
  EXPECT_EQ(r.existing_links(), 16u * 4u);
}

TEST(NetworkRouting, RingTakesTheShorterWayTiesClockwise) {
  const Routing r(Topology::ring, 7);
  for (unsigned s = 0; s < 7; ++s)
    for (unsigned d = 0; d < 7; ++d) {
      const unsigned forward = (d + 7 - s) % 7;
      EXPECT_EQ(r.hops(s, d), std::min(forward, 7 - forward));
      expect_connected_route(r, s, d);
    }
  const Routing even(Topology::ring, 8);
  std::vector<unsigned> links;
  even.route(0, 4, links);  // 4 either way: clockwise
  ASSERT_EQ(links.size(), 4u);
  EXPECT_EQ(even.link_name(links[0]), "0->1");
  even.route(0, 5, links);  // 5 clockwise, 3 counter-clockwise
  ASSERT_EQ(links.size(), 3u);
  EXPECT_EQ(even.link_name(links[0]), "0->7");
  even.route(6, 1, links);  // 3 clockwise across the wrap
  ASSERT_EQ(links.size(), 3u);
  EXPECT_EQ(even.link_name(links[2]), "0->1");
}

TEST(NetworkRouting, MeshIsAsSquareAsPossibleWithManhattanRoutesXFirst) {
  const Routing r(Topology::mesh, 9);
  EXPECT_EQ(r.mesh_columns(), 3u);
  EXPECT_EQ(r.mesh_rows(), 3u);
  EXPECT_EQ(r.existing_links(), 24u);  // 12 edges of a 3x3 grid, both ways
  for (int s = 0; s < 9; ++s)
    for (int d = 0; d < 9; ++d) {
      EXPECT_EQ(r.hops(s, d), static_cast<unsigned>(std::abs(s % 3 - d % 3) + std::abs(s / 3 - d / 3)));
      expect_connected_route(r, s, d);
    }
  std::vector<unsigned> links;
  r.route(0, 8, links);  // X first: 0 -> 1 -> 2, then down: 2 -> 5 -> 8
  ASSERT_EQ(links.size(), 4u);
  EXPECT_EQ(r.link_name(links[1]), "1->2");
  EXPECT_EQ(r.link_name(links[2]), "2->5");
  const Routing big(Topology::mesh, 128);
  EXPECT_EQ(big.mesh_columns(), 12u);  // ceil(sqrt(128))
  EXPECT_EQ(big.mesh_rows(), 11u);     // ceil(128 / 12)
}

TEST(NetworkRouting, AMeshWithAShortLastRowRoutesEveryPairInsideTheGrid) {
  for (unsigned p : {2u, 3u, 5u, 7u, 10u, 13u, 128u}) {
    const Routing r(Topology::mesh, p);
    const int cols = static_cast<int>(r.mesh_columns());
    for (int s = 0; s < static_cast<int>(p); ++s)
      for (int d = 0; d < static_cast<int>(p); ++d) {
        EXPECT_EQ(r.hops(s, d), static_cast<unsigned>(std::abs(s % cols - d % cols) + std::abs(s / cols - d / cols)))
            << p << ": " << s << "->" << d;
        expect_connected_route(r, s, d);
      }
  }
  // 7 nodes, 3 columns: node 6 alone in the last row; to 5 (column 2, row
  // 1) X first would pass the missing node 8, so the route goes up first.
  const Routing r(Topology::mesh, 7);
  std::vector<unsigned> links;
  r.route(6, 5, links);
  ASSERT_EQ(links.size(), 3u);
  EXPECT_EQ(r.link_name(links[0]), "6->3");
}

TEST(NetworkRouting, CrossbarIsTwoHopsInAndOutForEveryPair) {
  const Routing r(Topology::crossbar, 5);
  for (unsigned s = 0; s < 5; ++s)
    for (unsigned d = 0; d < 5; ++d) EXPECT_EQ(r.hops(s, d), s == d ? 0u : 2u);
  std::vector<unsigned> links;
  r.route(3, 1, links);
  ASSERT_EQ(links.size(), 2u);
  EXPECT_EQ(r.link_name(links[0]), "3->x");
  EXPECT_EQ(r.link_name(links[1]), "x->1");
}

TEST(NetworkModel, OneMessageTakesSetUpPlusHopsPlusBytesOverBandwidthOnEachTopology) {
  struct Case {
    Topology topology;
    unsigned nodes, src, dst, hops;
  };
  for (const Case& c : {Case{Topology::hypercube, 8, 0, 7, 3}, Case{Topology::mesh, 9, 0, 8, 4},
                        Case{Topology::ring, 8, 0, 5, 3}, Case{Topology::crossbar, 8, 0, 7, 2}}) {
    NetworkModel model(config(c.topology, c.nodes));
    const Delivery d = model.send(c.src, c.dst, 92, 1000 * NS);
    EXPECT_EQ(d.hops, c.hops) << topology_name(c.topology);
    EXPECT_EQ(d.inject_ps, 1000 * NS);
    EXPECT_EQ(d.start_ps, 1100 * NS);
    EXPECT_EQ(d.queue_ps, 0u);
    // 100 ns set-up + hops x 20 ns + 100 bytes x 5 ns.
    EXPECT_EQ(d.arrival_ps, (1000 + 100 + 20 * c.hops + 500) * NS) << topology_name(c.topology);
  }
}

TEST(NetworkModel, TransferTimeIsProportionalToTheBytesOnTheWire) {
  NetworkModel model(config(Topology::hypercube, 2));
  const Delivery a = model.send(0, 1, 192, 0);  // 200 bytes: 1000 ns
  const Delivery b = model.send(1, 0, 392, 0);  // 400 bytes: 2000 ns
  EXPECT_EQ(a.arrival_ps, (100 + 20 + 1000) * NS);
  EXPECT_EQ(b.arrival_ps, (100 + 20 + 2000) * NS);
  EXPECT_EQ(model.transfer_ps(7), 35 * NS);
  NetworkConfig fast = config(Topology::hypercube, 2);
  fast.link_mb_per_s = 400;  // twice the bandwidth: half the time
  NetworkModel quick(fast);
  EXPECT_EQ(quick.send(0, 1, 392, 0).arrival_ps, (100 + 20 + 1000) * NS);
  // Bandwidth that does not divide a picosecond rounds up.
  NetworkConfig odd = config(Topology::hypercube, 2);
  odd.link_mb_per_s = 3;  // 1 byte: 333333.3 ps
  EXPECT_EQ(NetworkModel(odd).transfer_ps(1), 333334u);
}

TEST(NetworkModel, TwoMessagesSharingALinkContendAndOnDisjointLinksDoNot) {
  NetworkModel model(config(Topology::hypercube, 4));
  // 0 -> 3 goes 0->1, 1->3; 1 -> 3 needs 1->3, which the first holds over
  // [120, 620) ns (its head reaches it one hop after starting at 100).
  const Delivery a = model.send(0, 3, 92, 0);
  const Delivery b = model.send(1, 3, 92, 0);
  EXPECT_EQ(a.arrival_ps, (100 + 40 + 500) * NS);
  EXPECT_EQ(b.start_ps, 620 * NS);
  EXPECT_EQ(b.queue_ps, 520 * NS);
  EXPECT_EQ(b.arrival_ps, (620 + 20 + 500) * NS);
  EXPECT_EQ(model.total_queue_ps(), 520 * NS);
  EXPECT_EQ(model.max_queue_ps(), 520 * NS);

  NetworkModel other(config(Topology::hypercube, 4));
  const Delivery c = other.send(0, 1, 92, 0);
  const Delivery d = other.send(2, 3, 92, 0);
  EXPECT_EQ(c.arrival_ps, 620 * NS);
  EXPECT_EQ(d.arrival_ps, 620 * NS);
  EXPECT_EQ(other.total_queue_ps(), 0u);
}

TEST(NetworkModel, TheCrossbarContendsOnlyAtASharedSourceOrDestinationPort) {
  NetworkModel model(config(Topology::crossbar, 4));
  EXPECT_EQ(model.send(0, 1, 92, 0).queue_ps, 0u);
  EXPECT_EQ(model.send(2, 3, 92, 0).queue_ps, 0u);  // other ports
  // Into node 1 again: its port x->1 carries the first over [120, 620).
  const Delivery into_same = model.send(3, 1, 92, 0);
  EXPECT_EQ(into_same.start_ps, 600 * NS);  // its head reaches x->1 at 620
  EXPECT_EQ(into_same.arrival_ps, (600 + 40 + 500) * NS);
  // Out of node 2 again: its port 2->x carries 2 -> 3 over [100, 600).
  EXPECT_EQ(model.send(2, 0, 92, 0).start_ps, 600 * NS);
}

TEST(NetworkModel, ACallOutOfTimeOrderFillsAGapBeforeAnEarlierReservation) {
  NetworkModel cube(config(Topology::hypercube, 4));
  // Node 2, ahead in its quantum, sends first: 2 -> 1 routes 2->3, 3->1
  // and holds 3->1 over [5120, 5620) ns.
  const Delivery late = cube.send(2, 1, 92, 5000 * NS);
  // Node 3, behind, needs 3->1 over [100, 600): the gap before is free.
  const Delivery early = cube.send(3, 1, 92, 0);
  EXPECT_EQ(late.queue_ps, 0u);
  EXPECT_EQ(early.queue_ps, 0u);
  EXPECT_EQ(early.arrival_ps, 620 * NS);
  // One that does not fit in the gap before [5120, 5620) waits behind it.
  const Delivery squeezed = cube.send(3, 1, 92, 4800 * NS);  // wants [4900, 5400)
  EXPECT_EQ(squeezed.start_ps, 5620 * NS);
}

TEST(NetworkModel, MessagesOfOnePairArriveInTheOrderTheyWereSent) {
  NetworkModel model(config(Topology::hypercube, 2));
  const Delivery big = model.send(0, 1, 992, 0);  // 1000 bytes: 5000 ns on 0->1 from 100
  const Delivery small = model.send(0, 1, 0, 0);  // 8 bytes, same time
  EXPECT_EQ(big.arrival_ps, (100 + 20 + 5000) * NS);
  EXPECT_EQ(small.start_ps, 5100 * NS);
  EXPECT_EQ(small.arrival_ps, (5100 + 20 + 40) * NS);
  EXPECT_GT(small.arrival_ps, big.arrival_ps);
  // A later call with an earlier inject time (its node behind in time)
  // still does not overtake: the gap before [100, 5100) on 0->1 is free,
  // but the pair's previous message started at 5100.
  const Delivery behind = model.send(0, 1, 0, 0);
  EXPECT_GE(behind.start_ps, small.start_ps);
  EXPECT_GE(behind.arrival_ps, small.arrival_ps);
  EXPECT_EQ(behind.start_ps, (5100 + 40) * NS);  // after small's 40 ns on 0->1
}

TEST(NetworkModel, AMessageToItselfCostsNothingAndUsesNoLink) {
  NetworkModel model(config(Topology::ring, 4));
  const Delivery d = model.send(2, 2, 1000, 700 * NS);
  EXPECT_EQ(d.hops, 0u);
  EXPECT_EQ(d.arrival_ps, 700 * NS);
  EXPECT_EQ(model.self_messages(), 1u);
  EXPECT_EQ(model.link_bytes(), 0u);
}

TEST(NetworkModel, StatisticsCountMessagesBytesLinksAndNodes) {
  NetworkModel model(config(Topology::hypercube, 4));
  model.send(0, 3, 92, 0);  // 2 hops
  model.send(1, 3, 92, 0);  // 1 hop, queued 520 ns
  model.send(2, 2, 10, 0);  // itself
  EXPECT_EQ(model.messages(), 3u);
  EXPECT_EQ(model.payload_bytes(), 194u);
  EXPECT_EQ(model.wire_bytes(), 200u);
  EXPECT_EQ(model.link_bytes(), 300u);
  EXPECT_EQ(model.total_hops(), 3u);
  EXPECT_EQ(model.node(3).messages_received, 2u);
  EXPECT_EQ(model.node(3).bytes_received, 184u);
  EXPECT_EQ(model.node(0).messages_sent, 1u);
  EXPECT_EQ(model.node(2).bytes_sent, 10u);
  // 3 links busy 500 ns each (1->3 twice: 1000 ns) over 2000 ns, 8 links.
  EXPECT_DOUBLE_EQ(model.max_link_utilisation(2000 * NS), 0.5);
  EXPECT_DOUBLE_EQ(model.mean_link_utilisation(2000 * NS), 1500.0 / 2000.0 / 8.0);
  EXPECT_EQ(model.last_arrival_ps(), 1140 * NS);
}

TEST(NetworkModel, PruningForgetsOnlyTheReservationsThatEnded) {
  NetworkModel model(config(Topology::hypercube, 2));
  model.send(0, 1, 92, 0);          // 0->1 over [100, 600)
  model.send(0, 1, 92, 1000 * NS);  // over [1100, 1600)
  model.prune(700 * NS);
  // Ready at 1050, the pair's last start 1100: the kept [1100, 1600)
  // still holds it back.
  EXPECT_EQ(model.send(0, 1, 92, 950 * NS).start_ps, 1600 * NS);
}

TEST(NetworkModel, BadParametersNameTheirKey) {
  expect_config_error(config(Topology::ring, 0), "cluster.nodes");
  expect_config_error(config(Topology::ring, 129), "cluster.nodes");
  expect_config_error(config(Topology::hypercube, 12), "cluster.nodes");
  try {
    NetworkModel model(config(Topology::hypercube, 12));
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("hypercube"), std::string::npos) << e.what();
  }
  NetworkConfig c = config(Topology::mesh, 12);
  c.link_mb_per_s = 0;
  expect_config_error(c, "network.link_mb_per_s");
  c.link_mb_per_s = -5;
  expect_config_error(c, "network.link_mb_per_s");
  c = config(Topology::mesh, 12);
  c.hop_latency_ns = -1;
  expect_config_error(c, "network.hop_latency_ns");
  c = config(Topology::mesh, 12);
  c.message_latency_ns = -0.5;
  expect_config_error(c, "network.message_latency_ns");
  try {
    parse_topology("torus");
    ADD_FAILURE() << "no error for torus";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("network.topology"), std::string::npos) << e.what();
  }
  EXPECT_EQ(parse_topology("crossbar"), Topology::crossbar);
  NetworkModel model(config(Topology::ring, 4));
  EXPECT_THROW(model.send(0, 4, 1, 0), std::out_of_range);
}

TEST(NetworkModel, OneNodeAndTwoNodeNetworksWork) {
  for (Topology t : {Topology::hypercube, Topology::mesh, Topology::ring, Topology::crossbar}) {
    NetworkModel one(config(t, 1));
    EXPECT_EQ(one.send(0, 0, 4, 10).arrival_ps, 10u);
    NetworkModel two(config(t, 2));
    EXPECT_EQ(two.send(0, 1, 92, 0).hops, t == Topology::crossbar ? 2u : 1u);
  }
}
