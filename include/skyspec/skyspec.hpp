// skyspec's public API in one include: scenes, rendering, spectra and colour, the physics a
// coefficient report derives, reports, errors and the version. Everything else is internal (src/).
#pragma once

#include "skyspec/atmosphere.hpp"
#include "skyspec/camera.hpp"
#include "skyspec/coefficient_report.hpp"
#include "skyspec/colour.hpp"
#include "skyspec/density_profile.hpp"
#include "skyspec/error.hpp"
#include "skyspec/geometry.hpp"
#include "skyspec/king_factor.hpp"
#include "skyspec/monte_carlo.hpp"
#include "skyspec/phase_function.hpp"
#include "skyspec/rayleigh.hpp"
#include "skyspec/refractive_index.hpp"
#include "skyspec/render.hpp"
#include "skyspec/scene.hpp"
#include "skyspec/sky_comparison.hpp"
#include "skyspec/spectrum.hpp"
#include "skyspec/standard_atmosphere.hpp"
#include "skyspec/units.hpp"
#include "skyspec/version.hpp"
