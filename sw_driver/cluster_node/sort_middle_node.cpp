#include "cluster_node/sort_middle_node.h"

#include <cstring>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cluster/cluster_scene.h"
#include "cluster/geometry.h"
#include "cluster/host_link_regs.h"
#include "cluster/node_memory_map.h"
#include "cluster/rasterize.h"
#include "cluster/scene.h"
#include "cluster/split.h"
#include "cluster/stripe_layout.h"
#include "cluster_node/host_charges.h"
#include "cluster_node/message_protocol.h"
#include "config/config.h"
#include "costs/host_cost.h"
#include "device/network_driver.h"

namespace tessera {

namespace {

using costs::HostCost;
using sort_middle::MessageType;
using sort_middle::tag_frame;
using sort_middle::tag_type;

// What a frame's time went to, per node (README.md, "Where the time goes"):
// the paper's components.
enum class Phase : unsigned { compute, split, send, wait, termination, count_ };
constexpr const char* PHASE_NAMES[] = {"compute", "split", "send", "wait", "termination"};

// The job, from the run's configuration (cluster.*), the same on every node.
struct Job {
  std::string scene;
  unsigned triangles = 0, triangle_pixels = 0, seed = 0;
  unsigned width = 0, height = 0, frames = 0;
  unsigned buffer_depth = 0;  // 0: auto

  static Job from(const AppEnvironment& env) {
    const Config& c = *env.config;
    Job job;
    job.scene = c.get_string("cluster.scene");
    job.triangles = static_cast<unsigned>(c.get_uint("cluster.triangles"));
    job.triangle_pixels = static_cast<unsigned>(c.get_uint("cluster.triangle_pixels"));
    job.seed = static_cast<unsigned>(c.get_uint("cluster.seed"));
    job.width = static_cast<unsigned>(c.get_uint("cluster.width"));
    job.height = static_cast<unsigned>(c.get_uint("cluster.height"));
    job.frames = env.frames;
    const std::string depth = c.get_string("cluster.buffer_depth");
    job.buffer_depth = depth == "auto" ? 0 : static_cast<unsigned>(std::stoul(depth));
    return job;
  }
};

class SortMiddleNode {
 public:
  // Where the split puts its pieces.
  class Sink : public cluster::TrapezoidSink {
   public:
    explicit Sink(SortMiddleNode& node) : m_node(node) {}
    void put(unsigned stripe, const cluster::Trapezoid& trapezoid) override { m_node.emit(stripe, trapezoid); }

   private:
    SortMiddleNode& m_node;
  };

  explicit SortMiddleNode(AppEnvironment& env);
  int run();

 private:
  void lay_out_memory();
  void load_database();
  void begin_frame(unsigned frame);
  void deal_triangles();
  void emit(unsigned stripe, const cluster::Trapezoid& trapezoid);
  void flush(unsigned destination);
  void send_control(unsigned destination, MessageType type);
  // Handles every message that has arrived; false when one of the next
  // frame's has (the frame is then complete everywhere).
  bool poll();
  void draw_received(const NetworkDriver::Message& message);
  void neighbour_complete();
  void node_complete();  // node 0: one more node's NC
  void terminate();
  void end_frame();
  void enter(Phase phase);
  // The core's work so far: geometry and split, and the stripe's drawing.
  cluster::WorkCounters counters() const;
  unsigned next_auto_depth() const;

  AppEnvironment& m_env;
  HostApi& m_host;
  NetworkDriver m_net;
  Job m_job;
  unsigned m_id, m_nodes;
  cluster::ClusterScene m_scene;
  HostStripeMemory m_memory;
  std::unique_ptr<cluster::Stripe> m_stripe;
  unsigned m_depth = 0;      // this frame's d
  unsigned m_max_depth = 0;  // what the buffers and slots hold

  // Two buffers per destination, d trapezoids each.
  uint32_t m_buffers = 0;
  uint32_t m_database = 0;  // the node's triangles, sizeof(WorldTriangle) each
  unsigned m_own_triangles = 0;
  uint32_t m_control_payload = 0;
  std::vector<unsigned> m_fill;        // trapezoids in the filling buffer
  std::vector<unsigned char> m_which;  // the filling buffer (0 or 1)
  std::vector<uint32_t> m_ticket[2];   // each buffer's send, while in flight
  std::vector<unsigned char> m_in_flight[2];
  std::vector<unsigned char> m_neighbour;  // sent to this frame

  unsigned m_frame = 0;
  unsigned m_neighbours = 0, m_ltc = 0, m_nc = 0;
  bool m_local_done = false, m_nc_sent = false, m_complete = false;

  Phase m_phase = Phase::compute;
  uint64_t m_phase_start = 0;
  uint64_t m_phase_cycles[static_cast<unsigned>(Phase::count_)] = {};
  uint64_t m_frame_start = 0;
  cluster::WorkCounters m_counters;        // geometry and split; the stripe counts its own
  cluster::WorkCounters m_frame_counters;  // counters() at the frame's start
  CostMeter m_meter;
  Sink m_sink{*this};
  uint64_t m_messages_sent = 0, m_messages_received = 0, m_trapezoids_sent = 0, m_trapezoids_received = 0;
};

static_assert(sizeof(cluster::WorldTriangle) % 4 == 0 && std::is_trivially_copyable_v<cluster::WorldTriangle>,
              "a triangle is kept in the node's memory as its words");

// cluster.buffer_depth=auto: the first frame's d, before any counts exist.
constexpr unsigned AUTO_FIRST_DEPTH = 16;
// The stripe's background, RGBA8 (r | g << 8 | b << 16 | a << 24): opaque black.
constexpr uint32_t CLEAR_COLOUR = 0xFF000000u;

// The core's counts of this frame (now - at its start) as frame figures.
void add_work_figures(const cluster::WorkCounters& now, const cluster::WorkCounters& start,
                      std::vector<std::pair<std::string, double>>& figures) {
  const auto add = [&](const char* name, uint64_t cluster::WorkCounters::*field) {
    figures.emplace_back(name, static_cast<double>(now.*field - start.*field));
  };
  add("triangles", &cluster::WorkCounters::triangles_in);
  add("triangles_culled", &cluster::WorkCounters::triangles_culled);
  add("triangles_rejected", &cluster::WorkCounters::triangles_rejected);
  add("triangles_split", &cluster::WorkCounters::triangles_split);
  add("trapezoids_made", &cluster::WorkCounters::trapezoids_out);
  add("trapezoids_drawn", &cluster::WorkCounters::trapezoids_in);
  add("rows", &cluster::WorkCounters::rows);
  add("pixels", &cluster::WorkCounters::pixels);
  add("depth_passes", &cluster::WorkCounters::depth_passes);
}

uint32_t align(uint32_t value, uint32_t alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

SortMiddleNode::SortMiddleNode(AppEnvironment& env)
    : m_env(env),
      m_host(*env.host),
      m_net(*env.host),
      m_job(Job::from(env)),
      m_id(m_net.id()),
      m_nodes(m_net.nodes()),
      m_memory(env.host) {
  m_scene =
      cluster::ClusterScene(m_job.scene, m_job.triangles, m_job.triangle_pixels, m_job.seed, m_job.width, m_job.height);
  lay_out_memory();
}

// From the heap's start: the stripe's colour (where the platform gathers
// it) and depth, the send ring, the send buffers, the receive ring.
void SortMiddleNode::lay_out_memory() {
  const unsigned rows = stripes::rows(m_id, m_job.height, m_nodes);
  const unsigned first = stripes::first_row(m_id, m_job.height, m_nodes);
  uint32_t next = m_env.heap_base;
  const uint32_t colour = next;
  m_host.write32(node_memory_map::host_link.base + host_link_regs::STRIPE_ADDRESS, colour);
  next += stripes::colour_bytes(m_id, m_job.width, m_job.height, m_nodes);
  const uint32_t depth = next;
  next += rows * m_job.width * 4;
  cluster::StripeBuffers buffers;
  buffers.width = m_job.width;
  buffers.first_row = first;
  buffers.rows = rows;
  buffers.color_format = PixelFormat::rgba8888;
  buffers.color_address = colour;
  buffers.depth_address = depth;
  m_stripe = std::make_unique<cluster::Stripe>(m_memory, buffers);

  const unsigned tx_count = 2 * m_nodes + 8;
  const uint32_t tx_base = align(next, 16);
  next = tx_base + NetworkDriver::tx_ring_bytes(tx_count);
  m_control_payload = next;
  next += 16;

  // The node's share of the scene (its triangles i = id, id + p, ...), made
  // once before the first frame: the paper's nodes read their triangles
  // from memory; making them (random orientations, lighting) is not part of
  // a frame.
  m_own_triangles = m_scene.triangles() > m_id ? (m_scene.triangles() - m_id + m_nodes - 1) / m_nodes : 0;
  m_database = align(next, 16);
  const uint64_t database_end = uint64_t{m_database} + uint64_t{m_own_triangles} * sizeof(cluster::WorldTriangle);
  if (database_end > m_env.memory_bytes)
    throw ProgramInputError("cluster.triangles: node " + std::to_string(m_id) + "'s " +
                            std::to_string(m_own_triangles) + " triangles of " +
                            std::to_string(sizeof(cluster::WorldTriangle)) +
                            " bytes do not fit its memory (cluster.node_memory_kib) beside its stripe");
  next = static_cast<uint32_t>(database_end);

  // d, or with "auto" the most the memory holds (at most 4096): two send
  // buffers per destination and a receive ring of 2 p + 2 slots.
  const unsigned rx_count = 2 * m_nodes + 2;
  const uint64_t free = m_env.memory_bytes > next ? m_env.memory_bytes - next : 0;
  const uint64_t per_depth = uint64_t{sizeof(cluster::Trapezoid)} * (2 * m_nodes + rx_count);
  const uint64_t fixed = uint64_t{rx_count} * NetworkDriver::HEADER_BYTES + 64;
  const uint64_t most = free > fixed ? (free - fixed) / per_depth : 0;
  m_max_depth = m_job.buffer_depth != 0 ? m_job.buffer_depth : static_cast<unsigned>(std::min<uint64_t>(most, 4096));
  if (m_max_depth == 0 || m_max_depth > most)
    throw ProgramInputError(
        "cluster.buffer_depth=" + std::to_string(m_job.buffer_depth) + ": " + std::to_string(m_nodes) +
        " nodes' send buffers and the receive ring of " + std::to_string(m_max_depth) + " trapezoids of " +
        std::to_string(sizeof(cluster::Trapezoid)) + " bytes do not fit node " + std::to_string(m_id) +
        "'s memory (cluster.node_memory_kib): at most " + std::to_string(most));
  m_depth = m_job.buffer_depth != 0 ? m_job.buffer_depth : AUTO_FIRST_DEPTH;
  m_depth = std::min(m_depth, m_max_depth);

  const uint32_t buffer_bytes = m_max_depth * sizeof(cluster::Trapezoid);
  m_buffers = align(next, 16);
  next = m_buffers + 2 * m_nodes * buffer_bytes;
  const unsigned slot_bytes = NetworkDriver::HEADER_BYTES + buffer_bytes;
  const uint32_t rx_base = align(next, 16);
  m_net.start({tx_base, tx_count, rx_base, rx_count, slot_bytes});

  m_fill.assign(m_nodes, 0);
  m_which.assign(m_nodes, 0);
  m_neighbour.assign(m_nodes, 0);
  for (unsigned b = 0; b < 2; ++b) {
    m_ticket[b].assign(m_nodes, 0);
    m_in_flight[b].assign(m_nodes, 0);
  }
}

void SortMiddleNode::enter(Phase phase) {
  const uint64_t now = m_host.now_cycles();
  m_phase_cycles[static_cast<unsigned>(m_phase)] += now - m_phase_start;
  m_phase_start = now;
  m_phase = phase;
}

cluster::WorkCounters SortMiddleNode::counters() const {
  cluster::WorkCounters all = m_counters;
  const cluster::WorkCounters& drawn = m_stripe->counters();
  all.trapezoids_in = drawn.trapezoids_in;
  all.rows = drawn.rows;
  all.spans = drawn.spans;
  all.pixels = drawn.pixels;
  all.depth_passes = drawn.depth_passes;
  return all;
}

// The paper's Eq. 11, d_opt = sqrt(2 (p - 1) v t_l / (alpha p)), from this
// node's own counts of the frame just drawn: v, the trapezoids it made per
// destination; t_l, its cycles per message sent (the send phase over the
// messages); alpha, its wait constant from the paper's wait time alpha p d
// / 2 (the wait phase at this frame's d). No wait: d as large as the
// buffers hold. In integers (one square root by bisection).
unsigned SortMiddleNode::next_auto_depth() const {
  const cluster::WorkCounters now = counters();
  const uint64_t made = now.trapezoids_out - m_frame_counters.trapezoids_out;
  const uint64_t send = m_phase_cycles[static_cast<unsigned>(Phase::send)];
  const uint64_t wait = m_phase_cycles[static_cast<unsigned>(Phase::wait)];
  if (m_nodes < 2 || m_messages_sent == 0 || made == 0) return m_depth;
  if (wait == 0) return m_max_depth;
  // d^2 = 2 (p - 1) (made / p) (send / messages) / (2 wait / (p d) * p)
  //     = (p - 1) made send d / (p messages wait)
  const double square =
      static_cast<double>(m_nodes - 1) * static_cast<double>(made) * static_cast<double>(send) * m_depth /
      (static_cast<double>(m_nodes) * static_cast<double>(m_messages_sent) * static_cast<double>(wait));
  unsigned d = 1;
  while (d < m_max_depth && static_cast<double>(d + 1) * (d + 1) <= square) ++d;
  return d;
}

void SortMiddleNode::load_database() {
  for (unsigned k = 0; k < m_own_triangles; ++k) {
    const cluster::WorldTriangle triangle = m_scene.triangle(m_id + k * m_nodes);
    m_host.write_words(m_database + k * sizeof(triangle), reinterpret_cast<const uint32_t*>(&triangle),
                       sizeof(triangle) / 4);
  }
}

int SortMiddleNode::run() {
  load_database();
  for (unsigned frame = 0; frame < m_job.frames; ++frame) {
    begin_frame(frame);
    deal_triangles();
    terminate();
    end_frame();
  }
  return 0;
}

void SortMiddleNode::begin_frame(unsigned frame) {
  m_frame = frame;
  m_frame_start = m_phase_start = m_host.now_cycles();
  m_phase = Phase::compute;
  for (uint64_t& cycles : m_phase_cycles) cycles = 0;
  m_frame_counters = counters();
  m_messages_sent = m_messages_received = m_trapezoids_sent = m_trapezoids_received = 0;
  m_neighbours = m_ltc = m_nc = 0;
  m_local_done = m_nc_sent = m_complete = false;
  for (unsigned j = 0; j < m_nodes; ++j) m_neighbour[j] = 0;
  cluster::clear_stripe(*m_stripe, CLEAR_COLOUR);
}

void SortMiddleNode::deal_triangles() {
  for (unsigned k = 0; k < m_own_triangles; ++k) {
    enter(Phase::compute);
    cluster::WorldTriangle triangle;
    m_host.read_words(m_database + k * sizeof(triangle), reinterpret_cast<uint32_t*>(&triangle), sizeof(triangle) / 4);
    cluster::ScreenTriangle screen;
    const cluster::GeometryResult result = cluster::transform_triangle(triangle, m_scene.view(), &screen, m_counters);
    m_meter.charge(m_host, counters());
    if (result != cluster::GeometryResult::accepted) continue;
    enter(Phase::split);
    cluster::split_triangle(screen, m_job.height, m_nodes, m_sink, &m_counters);
    m_meter.charge(m_host, counters());
    // Draw what has come in while the triangle was being split (the
    // paper's loop: a check for messages every triangle).
    if (!poll()) throw ProgramInputError("cluster_node: a message of the next frame before this one's end");
  }
  enter(Phase::send);
  for (unsigned j = 0; j < m_nodes; ++j)
    if (m_fill[j] != 0) flush(j);
  for (unsigned j = 0; j < m_nodes; ++j)
    if (m_neighbour[j]) {
      ++m_neighbours;
      send_control(j, MessageType::last_trapezoid);
    }
  m_local_done = true;
  enter(Phase::termination);
  neighbour_complete();
}

void SortMiddleNode::emit(unsigned stripe, const cluster::Trapezoid& trapezoid) {
  if (stripe == m_id) {
    const Phase was = m_phase;
    enter(Phase::compute);
    cluster::rasterize_trapezoid(trapezoid, *m_stripe);
    m_meter.charge(m_host, counters());
    enter(was);
    return;
  }
  const unsigned b = m_which[stripe];
  if (m_in_flight[b][stripe]) {
    // The buffer's last send has not been read out yet: wait for it.
    const Phase was = m_phase;
    enter(Phase::wait);
    m_net.wait_sent(m_ticket[b][stripe]);
    m_in_flight[b][stripe] = 0;
    enter(was);
  }
  const uint32_t at = m_buffers + ((stripe * 2 + b) * m_max_depth + m_fill[stripe]) * sizeof(trapezoid);
  m_host.write_words(at, reinterpret_cast<const uint32_t*>(&trapezoid), sizeof(trapezoid) / 4);
  if (++m_fill[stripe] == m_depth) {
    const Phase was = m_phase;
    enter(Phase::send);
    flush(stripe);
    enter(was);
  }
}

void SortMiddleNode::flush(unsigned destination) {
  const unsigned b = m_which[destination];
  const uint32_t at = m_buffers + (destination * 2 + b) * m_max_depth * sizeof(cluster::Trapezoid);
  m_ticket[b][destination] = m_net.send(destination, at, m_fill[destination] * sizeof(cluster::Trapezoid),
                                        make_tag(MessageType::trapezoids, m_frame));
  m_in_flight[b][destination] = 1;
  m_neighbour[destination] = 1;
  ++m_messages_sent;
  m_trapezoids_sent += m_fill[destination];
  m_fill[destination] = 0;
  m_which[destination] = static_cast<unsigned char>(1 - b);
}

void SortMiddleNode::send_control(unsigned destination, MessageType type) {
  m_net.send(destination, m_control_payload, 0, make_tag(type, m_frame));
  ++m_messages_sent;
}

bool SortMiddleNode::poll() {
  NetworkDriver::Message message;
  while (m_net.peek(message)) {
    const uint32_t frame = tag_frame(message.tag);
    if (frame + 1 == m_frame && tag_type(message.tag) == MessageType::global_completion) {
      m_net.release();  // the last frame's GC, after a message of this frame ended it here
      continue;
    }
    if (frame != m_frame) return false;  // the next frame's: this one is complete everywhere
    const Phase was = m_phase;
    ++m_messages_received;
    switch (tag_type(message.tag)) {
      case MessageType::trapezoids:
        enter(Phase::compute);
        draw_received(message);
        m_net.release();
        break;
      case MessageType::last_trapezoid:
        m_net.release();
        enter(Phase::send);
        send_control(message.source, MessageType::last_trapezoid_complete);
        break;
      case MessageType::last_trapezoid_complete:
        m_net.release();
        ++m_ltc;
        neighbour_complete();
        break;
      case MessageType::neighbours_complete:
        m_net.release();
        node_complete();
        break;
      case MessageType::global_completion:
        m_net.release();
        m_complete = true;
        break;
      default:
        throw ProgramInputError("cluster_node: message of unknown type " + std::to_string(message.tag & 0xFF) +
                                " from node " + std::to_string(message.source));
    }
    enter(was);
  }
  return true;
}

void SortMiddleNode::draw_received(const NetworkDriver::Message& message) {
  const unsigned count = message.bytes / sizeof(cluster::Trapezoid);
  cluster::Trapezoid trapezoid;
  for (unsigned k = 0; k < count; ++k) {
    m_host.read_words(message.payload + k * sizeof(trapezoid), reinterpret_cast<uint32_t*>(&trapezoid),
                      sizeof(trapezoid) / 4);
    cluster::rasterize_trapezoid(trapezoid, *m_stripe);
  }
  m_meter.charge(m_host, counters());
  m_trapezoids_received += count;
}

// When this node has sent its last trapezoids and every neighbour has drawn
// them: NC to node 0.
void SortMiddleNode::neighbour_complete() {
  if (!m_local_done || m_nc_sent || m_ltc != m_neighbours) return;
  m_nc_sent = true;
  if (m_id == 0)
    node_complete();
  else
    send_control(0, MessageType::neighbours_complete);
}

// Node 0, when every node's NC is in (its own included): the frame is
// complete; the platform gathers it, then every other node hears GC.
void SortMiddleNode::node_complete() {
  if (++m_nc != m_nodes) return;
  m_host.write32(node_memory_map::host_link.base + host_link_regs::FRAME_DONE, m_frame);
  for (unsigned j = 1; j < m_nodes; ++j) send_control(j, MessageType::global_completion);
  m_complete = true;
}

void SortMiddleNode::terminate() {
  while (!m_complete) {
    if (!poll()) break;  // the next frame has begun elsewhere: this one is complete
    if (m_complete) break;
    // Asleep until the others' last trapezoids, LTC, NC or GC come: the
    // end of the frame, the paper's termination (not its wait for a send
    // buffer, which alpha is).
    m_net.wait();
  }
}

void SortMiddleNode::end_frame() {
  enter(Phase::termination);
  std::vector<std::pair<std::string, double>> figures;
  figures.emplace_back("node", m_id);
  figures.emplace_back("cycles", static_cast<double>(m_host.now_cycles() - m_frame_start));
  for (unsigned i = 0; i < static_cast<unsigned>(Phase::count_); ++i)
    figures.emplace_back(std::string("cycles_") + PHASE_NAMES[i], static_cast<double>(m_phase_cycles[i]));
  figures.emplace_back("buffer_depth", m_depth);
  figures.emplace_back("messages_sent", static_cast<double>(m_messages_sent));
  figures.emplace_back("messages_received", static_cast<double>(m_messages_received));
  figures.emplace_back("trapezoids_sent", static_cast<double>(m_trapezoids_sent));
  figures.emplace_back("trapezoids_received", static_cast<double>(m_trapezoids_received));
  add_work_figures(counters(), m_frame_counters, figures);
  if (m_env.frame_statistics) m_env.frame_statistics(figures);
  if (m_job.buffer_depth == 0) m_depth = std::min(m_max_depth, next_auto_depth());
}

}  // namespace

int cluster_node_app(AppEnvironment& env) {
  // On the SoC the network interface's address is another block's.
  if (env.config == nullptr || !env.config->has("sim.platform") || env.config->get_string("sim.platform") != "cluster")
    throw ProgramInputError("cluster_node runs on the cluster platform only (soc_sim --platform cluster)");
  SortMiddleNode node(env);
  return node.run();
}

}  // namespace tessera
