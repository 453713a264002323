// Opening an OpenEXR file for reading in io/: the checks of exr_input.hpp first, then OpenEXR.
#pragma once

#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace skyspec {

/// check_exr_declared_sizes, then an Imf::InputFile (OpenEXR's exceptions pass through).
std::unique_ptr<Imf::InputFile> open_exr_input(const std::filesystem::path& path);

/// Throws IoError unless each named channel present in the header holds HALF or FLOAT samples
/// (a UINT channel is an id or a mask, not light: reading it as radiance would be wrong).
void require_float_channels(const Imf::Header& header, const std::vector<std::string>& names, const std::string& where);

}  // namespace skyspec
