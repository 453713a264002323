// Shared libraries opened on first use (dlopen) rather than at the process's start. GDAL (elevation
// data) and netCDF (a job's tables) bring many shared libraries with them, which every process
// would otherwise load before main (what that cost: docs/performance.md, "Start-up and the table
// cache"); only the commands that read a raster or write a NetCDF file open them. Their functions are called through
// pointers looked up once (io/elevation_raster.cpp, job/irradiance_netcdf.cpp).
#pragma once

#include <string>

namespace skyspec {

/// The library named `soname` (e.g. "libgdal.so.32"), opened once per process and kept open.
/// Throws Error naming the library and what it is needed for (`purpose`) when it cannot be opened.
void* open_shared_library(const std::string& soname, const std::string& purpose);

/// The address of `symbol` in a library open_shared_library returned; throws Error naming both when
/// it is missing.
void* shared_library_symbol(void* library, const std::string& soname, const char* symbol);

}  // namespace skyspec

// Declares `struct Api` with a pointer for each function FUNCTIONS lists (an X-macro: X(name) per
// function, declared by the library's header) and `const Api& getter()`, which opens SONAME on
// first use, looks every function up once and throws (naming the library and PURPOSE) if it cannot.
// clang-format off
#define SKYSPEC_SHARED_LIBRARY_API(Api, getter, FUNCTIONS, SONAME, PURPOSE)                  \
  struct Api {                                                                               \
    FUNCTIONS(SKYSPEC_SHARED_LIBRARY_POINTER)                                                \
  };                                                                                         \
  const Api& getter() {                                                                      \
    static const Api api = [] {                                                              \
      void* library = ::skyspec::open_shared_library(SONAME, PURPOSE);                       \
      Api a;                                                                                 \
      const char* soname = SONAME;                                                           \
      FUNCTIONS(SKYSPEC_SHARED_LIBRARY_LOOKUP)                                               \
      return a;                                                                              \
    }();                                                                                     \
    return api;                                                                              \
  }
#define SKYSPEC_SHARED_LIBRARY_POINTER(f) decltype(&::f) f = nullptr;
#define SKYSPEC_SHARED_LIBRARY_LOOKUP(f) \
  a.f = reinterpret_cast<decltype(&::f)>(::skyspec::shared_library_symbol(library, soname, #f));
// clang-format on
