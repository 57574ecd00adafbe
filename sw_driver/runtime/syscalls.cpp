// newlib's system calls for a bare-metal program on the ISS, over
// semihosting (semihosting_call.h): the console and the host's files
// (read-only) through SYS_OPEN/READ/WRITE, time from SYS_ELAPSED, the exit
// status through SYS_EXIT_EXTENDED; the heap grows from the end of .bss
// (`end`) up to the stacks (__heap_limit), both from the generated linker
// script. ARM only.
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/times.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "runtime/semihosting_call.h"

using tessera::runtime::semihosting_call;
namespace semihosting = tessera::runtime::semihosting;

extern "C" {
extern char end;           // the end of .bss: the heap's start
extern char __heap_limit;  // NOLINT(bugprone-reserved-identifier): the linker script's name
}

namespace {

// newlib's file descriptors and the semihosting handles behind them (0: closed).
constexpr int MAX_FILES = 16;
uint32_t g_handles[MAX_FILES];
char* g_break = &end;
// The second region the heap continues in (boot information), once the
// first is used up; newlib's malloc takes the jump as foreign memory.
char* g_second_base = nullptr;
char* g_second_end = nullptr;

int set_errno(int error) {
  errno = error;
  return -1;
}

// SYS_ERRNO's value (the service uses newlib's numbers) into errno.
int semihosting_failed() {
  return set_errno(static_cast<int>(semihosting_call(semihosting::errno_value, nullptr)));
}

uint32_t open_handle(const char* name, uint32_t mode) {
  const uint32_t block[3] = {reinterpret_cast<uint32_t>(name), mode, static_cast<uint32_t>(std::strlen(name))};
  return semihosting_call(semihosting::open, block);
}

uint32_t handle_of(int fd) {
  return fd >= 0 && fd < MAX_FILES ? g_handles[fd] : 0;
}

uint64_t elapsed_cycles() {
  uint32_t words[2] = {0, 0};
  semihosting_call(semihosting::elapsed, words);
  return uint64_t{words[0]} | uint64_t{words[1]} << 32;
}

}  // namespace

namespace tessera::runtime {

// stdin, stdout and stderr: the console, opened as semihosting asks (modes
// "r", "w" and "a").
void open_standard_streams() {
  g_handles[0] = open_handle(":tt", 0);
  g_handles[1] = open_handle(":tt", 4);
  g_handles[2] = open_handle(":tt", 8);
}

uint64_t cycles_since_start() {
  return elapsed_cycles();
}

void set_second_heap(uint32_t base, uint32_t end) {
  g_second_base = reinterpret_cast<char*>(base);
  g_second_end = reinterpret_cast<char*>(end);
}

uint32_t clock_hz() {
  static const uint32_t hz = semihosting_call(semihosting::tickfreq, nullptr);
  return hz;
}

}  // namespace tessera::runtime

extern "C" {

int _open(const char* name, int flags, ...) {  // NOLINT(bugprone-reserved-identifier): newlib's names
  int fd = 0;
  while (fd < MAX_FILES && g_handles[fd] != 0) ++fd;
  if (fd == MAX_FILES) return set_errno(EMFILE);
  // fopen's mode strings in semihosting's order: r, rb, r+, r+b, w, wb, w+,
  // w+b, a, ab, a+, a+b; newlib's flags carry no "b".
  uint32_t mode = 0;
  if ((flags & O_ACCMODE) == O_RDWR) mode = 2;
  if (flags & (O_CREAT | O_TRUNC)) mode = (flags & O_ACCMODE) == O_RDWR ? 6 : 4;
  if (flags & O_APPEND) mode = (flags & O_ACCMODE) == O_RDWR ? 10 : 8;
  const uint32_t handle = open_handle(name, mode);
  if (handle == 0xffffffffu) return semihosting_failed();
  g_handles[fd] = handle;
  return fd;
}

int _close(int fd) {
  const uint32_t handle = handle_of(fd);
  if (handle == 0) return set_errno(EBADF);
  g_handles[fd] = 0;
  if (fd <= 2) return 0;  // the console stays open
  return semihosting_call(semihosting::close, &handle) == 0 ? 0 : semihosting_failed();
}

int _write(int fd, const char* data, int length) {
  const uint32_t handle = handle_of(fd);
  if (handle == 0) return set_errno(EBADF);
  const uint32_t block[3] = {handle, reinterpret_cast<uint32_t>(data), static_cast<uint32_t>(length)};
  const uint32_t not_written = semihosting_call(semihosting::write, block);
  if (not_written == 0xffffffffu) return semihosting_failed();
  if (not_written == static_cast<uint32_t>(length) && length > 0) return set_errno(EBADF);
  return length - static_cast<int>(not_written);
}

int _read(int fd, char* data, int length) {
  const uint32_t handle = handle_of(fd);
  if (handle == 0) return set_errno(EBADF);
  const uint32_t block[3] = {handle, reinterpret_cast<uint32_t>(data), static_cast<uint32_t>(length)};
  const uint32_t not_read = semihosting_call(semihosting::read, block);
  if (not_read == 0xffffffffu) return semihosting_failed();
  return length - static_cast<int>(not_read);
}

int _lseek(int fd, int offset, int whence) {
  const uint32_t handle = handle_of(fd);
  if (handle == 0) return set_errno(EBADF);
  int position = offset;
  if (whence == SEEK_END) {
    const uint32_t length = semihosting_call(semihosting::flen, &handle);
    if (length == 0xffffffffu) return semihosting_failed();
    position += static_cast<int>(length);
  } else if (whence != SEEK_SET) {
    return set_errno(EINVAL);  // SEEK_CUR: semihosting keeps no position to add to
  }
  const uint32_t block[2] = {handle, static_cast<uint32_t>(position)};
  return semihosting_call(semihosting::seek, block) == 0 ? position : semihosting_failed();
}

int _fstat(int fd, struct stat* st) {
  const uint32_t handle = handle_of(fd);
  if (handle == 0) return set_errno(EBADF);
  std::memset(st, 0, sizeof *st);
  if (semihosting_call(semihosting::istty, &handle) == 1) {
    st->st_mode = S_IFCHR;
    return 0;
  }
  st->st_mode = S_IFREG;
  const uint32_t length = semihosting_call(semihosting::flen, &handle);
  if (length != 0xffffffffu) st->st_size = static_cast<off_t>(length);
  return 0;
}

int _isatty(int fd) {
  const uint32_t handle = handle_of(fd);
  if (handle == 0) return set_errno(EBADF), 0;
  return semihosting_call(semihosting::istty, &handle) == 1 ? 1 : 0;
}

void* _sbrk(ptrdiff_t increment) {
  const bool in_second = g_second_base != nullptr && g_break >= g_second_base && g_break <= g_second_end;
  char* const low = in_second ? g_second_base : &end;
  char* const high = in_second ? g_second_end : &__heap_limit;
  if (increment > high - g_break || increment < low - g_break) {
    if (in_second || g_second_base == nullptr || increment < 0 || increment > g_second_end - g_second_base) {
      errno = ENOMEM;
      return reinterpret_cast<void*>(-1);
    }
    g_break = g_second_base;  // the first region is used up: on in the second
  }
  char* previous = g_break;
  g_break += increment;
  return previous;
}

[[noreturn]] void _exit(int status) {
  const uint32_t block[2] = {semihosting::APPLICATION_EXIT, static_cast<uint32_t>(status)};
  semihosting_call(semihosting::exit_extended, block);
  for (;;) {
  }
}

int _kill(int /*pid*/, int /*signal*/) {
  return set_errno(EINVAL);
}

int _getpid() {
  return 1;
}

int _gettimeofday(struct timeval* tv, void* /*timezone*/) {
  const uint64_t cycles = elapsed_cycles();
  const uint32_t hz = tessera::runtime::clock_hz();
  tv->tv_sec = static_cast<time_t>(cycles / hz);
  tv->tv_usec = static_cast<suseconds_t>(cycles % hz * 1000000 / hz);
  return 0;
}

clock_t _times(struct tms* buffer) {
  const auto ticks = static_cast<clock_t>(elapsed_cycles() * CLOCKS_PER_SEC / tessera::runtime::clock_hz());
  if (buffer != nullptr) *buffer = {ticks, 0, 0, 0};
  return ticks;
}

int _unlink(const char* /*name*/) {
  return set_errno(EACCES);  // the host's files are read-only to a simulated program
}

int _link(const char* /*from*/, const char* /*to*/) {
  return set_errno(EACCES);
}

int _stat(const char* /*name*/, struct stat* /*st*/) {
  return set_errno(ENOSYS);
}

// std::random_device's source: a simulated program has no entropy to offer.
int getentropy(void* /*buffer*/, size_t /*length*/) {
  return set_errno(ENOSYS);
}

}  // extern "C"
