// Unit tests of the display driver (sw_driver/device/display_driver.h) on a
// RecordingHost: what it reads and writes, in order, word for word. Port
// mode copies the back buffer to the display port in bursts of eight words
// and writes PRESENT; DMA mode writes BACK_BASE and SWAP, waits for the
// swap-done interrupt (acknowledging every interrupt it sees) and draws the
// next frame into the other buffer; an unknown pixel format is an error
// naming the code and the known formats. The registers and their bits come
// from display_regs.def, as the driver's do.
#include <gtest/gtest.h>

#include <cstring>
#include <deque>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/pixel_format.h"
#include "device/display_driver.h"
#include "display/display_regs.h"
#include "host/cost_units.h"
#include "host/recording_host.h"
#include "soc/irq_map.h"
#include "soc/memory_map.h"

namespace tessera {
namespace {

namespace regs = display_regs;
using Access = test::RecordingHost::Access;
using Kind = Access::Kind;

constexpr uint32_t BUFFER0 = 0x10000, BUFFER1 = 0x40000;
constexpr uint32_t MEMORY_BYTES = 0x80000;
constexpr uint32_t PORT = memory_map::display_port.base;

uint32_t reg(uint32_t offset) {
  return memory_map::display_regs.base + offset;
}

// The display controller's registers as the driver reads them; IRQ_STATUS
// answers from a script, one value per read.
struct FakeDisplay {
  uint32_t width = 5, height = 3;
  uint32_t format = static_cast<uint32_t>(PixelFormat::rgb565);
  uint32_t mode = 0;
  std::deque<uint32_t> irq_status;

  uint32_t read(uint32_t address) {
    switch (address - memory_map::display_regs.base) {
      case regs::WIDTH: return width;
      case regs::HEIGHT: return height;
      case regs::FORMAT: return format;
      case regs::MODE: return mode;
      case regs::IRQ_STATUS: {
        if (irq_status.empty()) throw std::logic_error("the driver reads IRQ_STATUS more often than the test expects");
        const uint32_t value = irq_status.front();
        irq_status.pop_front();
        return value;
      }
      default: throw std::logic_error("the driver reads an unexpected address " + std::to_string(address));
    }
  }
};

class DisplayDriverTest : public ::testing::Test {
 protected:
  DisplayDriverTest() : host(MEMORY_BYTES) {
    host.read_register = [this](uint32_t address) { return display.read(address); };
    env.host = &host;
    env.frame_buffers[0] = BUFFER0;
    env.frame_buffers[1] = BUFFER1;
  }
  // Fills `bytes` of the buffer at `address` with a pattern no two frames share.
  void fill(uint32_t address, uint32_t bytes, uint8_t seed) {
    uint8_t* p = host.memory(address, bytes);
    for (uint32_t i = 0; i < bytes; ++i) p[i] = static_cast<uint8_t>(seed + 7 * i + (i >> 8));
  }
  uint32_t memory_word(uint32_t address) {
    uint32_t word = 0;
    std::memcpy(&word, host.memory(address, 4), 4);
    return word;
  }

  test::RecordingHost host;
  FakeDisplay display;
  AppEnvironment env;
};

void expect_access(const Access& a, Kind kind, uint32_t address, unsigned bytes, uint32_t value) {
  EXPECT_EQ(a.kind, kind) << "at address " << address;
  EXPECT_EQ(a.address, address);
  EXPECT_EQ(a.bytes, bytes) << "at address " << address;
  EXPECT_EQ(a.value, value) << "at address " << address;
}
void expect_read(const Access& a, uint32_t address, uint32_t value) {
  expect_access(a, Kind::read, address, 4, value);
}
void expect_write(const Access& a, uint32_t address, uint32_t value) {
  expect_access(a, Kind::write, address, 4, value);
}

TEST_F(DisplayDriverTest, PortModeSetUpReadsTheGeometryAndWritesNothing) {
  const DisplayDriver driver(env);
  ASSERT_EQ(host.log().size(), 4u);
  expect_read(host.log()[0], reg(regs::WIDTH), 5);
  expect_read(host.log()[1], reg(regs::HEIGHT), 3);
  expect_read(host.log()[2], reg(regs::FORMAT), 0);
  expect_read(host.log()[3], reg(regs::MODE), 0);
  EXPECT_EQ(driver.width(), 5u);
  EXPECT_EQ(driver.height(), 3u);
  EXPECT_EQ(driver.format(), PixelFormat::rgb565);
  EXPECT_EQ(driver.bytes_per_pixel(), 2u);
  EXPECT_EQ(driver.stride(), 10u);
  EXPECT_FALSE(driver.dma());
  EXPECT_EQ(driver.back_buffer(), BUFFER0);
}

// 5 x 3 RGB565 = 30 bytes: one LDM/STM burst of seven words, then the
// trailing half-word, then PRESENT.
TEST_F(DisplayDriverTest, PortModeCopiesTheBackBufferThenWritesPresent) {
  DisplayDriver driver(env);
  fill(BUFFER0, 30, 11);
  host.clear_log();
  tessera::test::take_cost_units();
  driver.present();
  const std::vector<Access>& log = host.log();
  ASSERT_EQ(log.size(), 5u);
  EXPECT_EQ(log[0].kind, Kind::load_span);
  EXPECT_EQ(log[0].address, BUFFER0);
  EXPECT_EQ(log[0].bytes, 4u);
  EXPECT_EQ(log[0].count, 7u);
  EXPECT_EQ(log[1].kind, Kind::write_words);
  EXPECT_EQ(log[1].address, PORT);
  ASSERT_EQ(log[1].words.size(), 7u);
  for (unsigned i = 0; i < 7; ++i) EXPECT_EQ(log[1].words[i], memory_word(BUFFER0 + 4 * i)) << "word " << i;
  uint16_t tail = 0;
  std::memcpy(&tail, host.memory(BUFFER0 + 28, 2), 2);
  expect_access(log[2], Kind::read, BUFFER0 + 28, 2, tail);
  expect_access(log[3], Kind::write, PORT + 28, 2, tail);
  expect_write(log[4], reg(regs::PRESENT), 1);
  // One burst charged (the loop around the LDM/STM; the trailing half-word is the access alone).
  EXPECT_EQ(tessera::test::take_cost_units()["display_copy_block"], 1u);
  // Port mode draws into the same buffer again.
  EXPECT_EQ(driver.back_buffer(), BUFFER0);
  driver.present();
  EXPECT_EQ(host.log().back().address, reg(regs::PRESENT));
  EXPECT_EQ(host.log()[5].address, BUFFER0);
}

// The default display: 320 x 240 RGB565 = 38,400 words in 4,800 bursts of
// eight, every word of the back buffer written to the same offset of the
// port, in order, and nothing else but PRESENT.
TEST_F(DisplayDriverTest, PortModeCopiesAFullFrameWordForWord) {
  display.width = 320;
  display.height = 240;
  DisplayDriver driver(env);
  const uint32_t bytes = 320 * 240 * 2;
  fill(BUFFER0, bytes, 3);
  host.clear_log();
  tessera::test::take_cost_units();
  driver.present();
  uint32_t offset = 0;
  size_t bursts = 0;
  for (const Access& a : host.log()) {
    if (a.kind == Kind::load_span) {
      EXPECT_EQ(a.address, BUFFER0 + offset);
      EXPECT_EQ(a.count, 8u);
      continue;
    }
    if (a.kind != Kind::write_words) break;
    ++bursts;
    ASSERT_EQ(a.address, PORT + offset);
    ASSERT_EQ(a.words.size(), 8u);
    for (unsigned i = 0; i < 8; ++i) ASSERT_EQ(a.words[i], memory_word(BUFFER0 + offset + 4 * i)) << offset;
    offset += 32;
  }
  EXPECT_EQ(bursts, 4800u);
  EXPECT_EQ(offset, bytes);
  ASSERT_EQ(host.log().size(), 2 * bursts + 1);
  expect_write(host.log().back(), reg(regs::PRESENT), 1);
  EXPECT_EQ(tessera::test::take_cost_units()["display_copy_block"], bursts);
}

TEST_F(DisplayDriverTest, PortModeRgba8888HasNoTrailingHalfWord) {
  display.width = 4;
  display.height = 4;
  display.format = static_cast<uint32_t>(PixelFormat::rgba8888);
  DisplayDriver driver(env);
  EXPECT_EQ(driver.bytes_per_pixel(), 4u);
  EXPECT_EQ(driver.stride(), 16u);
  fill(BUFFER0, 64, 5);
  host.clear_log();
  driver.present();
  const std::vector<Access>& log = host.log();
  ASSERT_EQ(log.size(), 5u);  // two bursts of eight words, PRESENT
  for (unsigned burst = 0; burst < 2; ++burst) {
    EXPECT_EQ(log[2 * burst].kind, Kind::load_span);
    EXPECT_EQ(log[2 * burst + 1].address, PORT + 32 * burst);
    for (unsigned i = 0; i < 8; ++i) EXPECT_EQ(log[2 * burst + 1].words[i], memory_word(BUFFER0 + 32 * burst + 4 * i));
  }
  expect_write(log[4], reg(regs::PRESENT), 1);
}

TEST_F(DisplayDriverTest, DmaModeSetUpEnablesTheSwapInterruptAndScanOut) {
  display.mode = 1;
  const DisplayDriver driver(env);
  EXPECT_TRUE(driver.dma());
  ASSERT_EQ(host.log().size(), 6u);
  expect_read(host.log()[3], reg(regs::MODE), 1);
  expect_write(host.log()[4], reg(regs::IRQ_ENABLE), regs::IRQ_SWAP_DONE);
  expect_write(host.log()[5], reg(regs::CTRL), regs::CTRL_ENABLE);
  EXPECT_EQ(driver.back_buffer(), BUFFER0);
}

// Present: BACK_BASE, SWAP, then sleep until the display's interrupt,
// acknowledging what IRQ_STATUS holds (write 1 to clear) until swap done
// was among it; the next frame goes to the other buffer.
TEST_F(DisplayDriverTest, DmaModeSwapsWaitsForSwapDoneAndAlternatesBuffers) {
  display.mode = 1;
  DisplayDriver driver(env);
  host.clear_log();
  tessera::test::take_cost_units();
  // A vertical blank first (not the swap), then the swap with a blank.
  display.irq_status = {regs::IRQ_VBLANK, regs::IRQ_VBLANK | regs::IRQ_SWAP_DONE};
  driver.present();
  const std::vector<Access>& log = host.log();
  ASSERT_EQ(log.size(), 8u);
  expect_write(log[0], reg(regs::BACK_BASE), BUFFER0);
  expect_write(log[1], reg(regs::SWAP), 1);
  EXPECT_EQ(log[2].kind, Kind::wait_irq);
  EXPECT_EQ(log[2].address, irq_map::display);
  expect_read(log[3], reg(regs::IRQ_STATUS), regs::IRQ_VBLANK);
  expect_write(log[4], reg(regs::IRQ_STATUS), regs::IRQ_VBLANK);
  EXPECT_EQ(log[5].kind, Kind::wait_irq);
  expect_read(log[6], reg(regs::IRQ_STATUS), regs::IRQ_VBLANK | regs::IRQ_SWAP_DONE);
  expect_write(log[7], reg(regs::IRQ_STATUS), regs::IRQ_VBLANK | regs::IRQ_SWAP_DONE);
  EXPECT_EQ(driver.back_buffer(), BUFFER1);

  // The next frames alternate: BUFFER1, then BUFFER0 again.
  for (uint32_t shown : {BUFFER1, BUFFER0}) {
    host.clear_log();
    display.irq_status = {regs::IRQ_SWAP_DONE};
    driver.present();
    ASSERT_EQ(host.log().size(), 5u);
    expect_write(host.log()[0], reg(regs::BACK_BASE), shown);
    expect_write(host.log()[4], reg(regs::IRQ_STATUS), regs::IRQ_SWAP_DONE);
    EXPECT_EQ(driver.back_buffer(), shown == BUFFER0 ? BUFFER1 : BUFFER0);
  }
  // The host copies nothing in DMA mode: the display fetches the buffer.
  EXPECT_EQ(tessera::test::take_cost_units()["display_copy_block"], 0u);
}

TEST_F(DisplayDriverTest, UnknownPixelFormatIsAClearError) {
  display.format = 7;
  display.mode = 1;
  try {
    const DisplayDriver driver(env);
    FAIL() << "a display with format code 7 was accepted";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("pixel format code 7"), std::string::npos) << message;
    EXPECT_NE(message.find(pixel_format_names()), std::string::npos) << message;
  }
  // Nothing was written to the display before the error.
  for (const Access& a : host.log()) EXPECT_EQ(a.kind, Kind::read);
}

}  // namespace
}  // namespace tessera
