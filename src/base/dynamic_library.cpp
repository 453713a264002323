#include "base/dynamic_library.hpp"

#include <dlfcn.h>

#include <map>
#include <mutex>

#include "skyspec/error.hpp"

namespace skyspec {

void* open_shared_library(const std::string& soname, const std::string& purpose) {
  static std::mutex mutex;
  static std::map<std::string, void*> opened;
  const std::lock_guard<std::mutex> lock(mutex);
  if (const auto it = opened.find(soname); it != opened.end()) return it->second;
  // RTLD_LOCAL: its symbols stay its own; RTLD_NOW: a broken installation fails here, not later.
  void* handle = dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw Error("cannot load " + soname + ", which " + purpose + " needs" + (why ? std::string(" (") + why + ")" : "") +
                ": install it (Debian: the package that holds " + soname + ")");
  }
  opened.emplace(soname, handle);
  return handle;
}

void* shared_library_symbol(void* library, const std::string& soname, const char* symbol) {
  dlerror();
  void* address = dlsym(library, symbol);
  if (!address) throw Error(soname + " has no function " + symbol + ": a version skyspec was not built for");
  return address;
}

}  // namespace skyspec
