#pragma once
namespace skyspec {
/// The library version, "MAJOR.MINOR.PATCH".
const char* version_string();
}  // namespace skyspec
