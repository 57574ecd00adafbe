#include "launch/app_loading.h"

#include <dlfcn.h>
#include <link.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "apps/apps.h"
#include "apps/gl_apps.h"
#include "cluster_node/sort_middle_node.h"
#include "host/iss/elf_image.h"

namespace tessera {

namespace {

// `name` as defined by the library `handle` itself, or nullptr: dlsym also
// finds symbols of the libraries it depends on, and a `main` there is not
// the application's.
void* own_symbol(void* handle, const char* name) {
  void* symbol = dlsym(handle, name);
  if (!symbol) return nullptr;
  link_map* library = nullptr;
  link_map* defining = nullptr;
  Dl_info info;
  if (dlinfo(handle, RTLD_DI_LINKMAP, &library) != 0 ||
      !dladdr1(symbol, &info, reinterpret_cast<void**>(&defining), RTLD_DL_LINKMAP))
    return nullptr;
  return defining == library ? symbol : nullptr;
}

}  // namespace

GlMain load_app_library(const std::string& path) {
  // A name without a slash would be searched in the library path; an
  // application is a file the user names.
  const std::string file = path.find('/') == std::string::npos ? "./" + path : path;
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) throw std::invalid_argument(std::string("cannot load application library: ") + dlerror());
  // tessera_app_main first, so a program that also builds natively with its
  // own main can say which one soc_sim runs; then an ordinary program's main.
  if (void* symbol = own_symbol(handle, "tessera_app_main")) return reinterpret_cast<GlMain>(symbol);
  if (void* symbol = own_symbol(handle, "main")) return reinterpret_cast<GlMain>(symbol);
  dlclose(handle);
  throw std::invalid_argument("application library '" + path + "' exports neither tessera_app_main nor main");
}

namespace {

// <the running program's folder>/arm922t/<file>, which must exist; `what`
// says what it is for.
std::string iss_image(const char* file, const std::string& what) {
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  const std::filesystem::path image = self.parent_path() / "arm922t" / file;
  if (error || !std::filesystem::exists(image))
    throw std::invalid_argument("host.model=iss runs " + what + " from " + image.string() +
                                ", which is missing: the build makes it when arm-none-eabi-g++ is installed "
                                "(scripts/setup.sh; sw_driver/runtime/README.md)");
  return image.string();
}

}  // namespace

std::string builtin_iss_image() {
  return iss_image("tessera_apps.elf", "the built-in applications");
}

LaunchableApp cluster_node_program(bool on_iss) {
  constexpr const char* DESCRIPTION = "the sort-middle renderer's node program";
  if (!on_iss) return {[](AppEnvironment& env, const IssHost&) { return cluster_node_app(env); }, DESCRIPTION};
  const std::string image = iss_image("tessera_cluster_node.elf", "the cluster's node program");
  return {[image](AppEnvironment& env, const IssHost& iss_host) {
            return run_elf_app(env, iss_host, image, "cluster_node");
          },
          std::string(DESCRIPTION) + " (cross-compiled, on the ISS)"};
}

LaunchableApp find_app(const std::string& name, bool on_iss) {
  const auto& apps = builtin_apps();
  auto it = apps.find(name);
  if (it != apps.end()) {
    if (!on_iss) {
      const AppMain main = it->second.main;
      return {[main](AppEnvironment& env, const IssHost&) { return main(env); }, it->second.description};
    }
    const std::string image = builtin_iss_image();
    return {
        [image, name](AppEnvironment& env, const IssHost& iss_host) { return run_elf_app(env, iss_host, image, name); },
        it->second.description + " (cross-compiled, on the ISS)"};
  }
  if (is_elf_app(name)) {
    try {
      (void)iss::read_elf(name);  // bad input is the command line's error, before the simulation
    } catch (const iss::ElfError& e) {
      throw std::invalid_argument(e.what());
    }
    return {[name](AppEnvironment& env, const IssHost& iss_host) { return run_elf_app(env, iss_host, name); },
            "ARM executable " + name + " on the ISS"};
  }
  if (name.find('/') != std::string::npos || name.find(".so") != std::string::npos) {
    if (on_iss)
      throw std::invalid_argument("application library '" + name +
                                  "' is host-compiled and host.model=iss runs ARM executables: build the application "
                                  "as an ARM executable with the SDK's toolchain file (sw_driver/runtime/README.md), "
                                  "or run it with host.model=native");
    const GlMain main = load_app_library(name);
    return {[main, name](AppEnvironment& env, const IssHost&) { return run_gl_app(env, main, name); },
            "application library " + name};
  }
  throw std::invalid_argument("unknown application '" + name + "' (built-in: " + builtin_app_names() +
                              "; or the path of a shared library exporting tessera_app_main or main, or of an ARM "
                              "executable *.elf)");
}

}  // namespace tessera
