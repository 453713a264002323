#include "transport/scattering_tables_key.hpp"

#include <cstdio>
#include <iomanip>
#include <sstream>

#include "base/embedded_data.hpp"
#include "skyspec/phase_function.hpp"

namespace skyspec {
namespace {

template <typename Array>
void write_array(std::ostream& out, const char* name, const Array& a) {
  out << name;
  for (const auto& v : a) out << ' ' << static_cast<double>(v);
  out << '\n';
}

// A medium as the tables see it: its profile, coefficients and phase function per wavelength.
void write_medium(std::ostream& out, const Medium& m) {
  const std::string& name = m.name;
  out << name << ".profile " << m.profile.describe() << '\n';
  // Confined to a region, it is left out of the field (with_regional_media_as_probes), wherever the
  // region stands.
  if (m.region) out << name << ".region: a probe of the field\n";
  write_array(out, (name + ".scattering_per_m").c_str(), m.scattering_per_m);
  write_array(out, (name + ".extinction_per_m").c_str(), m.extinction_per_m);
  const MediumPhase& p = m.phase;
  switch (p.kind) {
    case MediumPhase::Kind::None:
      break;
    case MediumPhase::Kind::Rayleigh:
      write_array(out, (name + ".phase.rayleigh_gamma").c_str(), p.rayleigh_gamma);
      break;
    case MediumPhase::Kind::Analytic:
      out << name << ".phase " << to_string(p.analytic_model) << '\n';
      write_array(out, (name + ".phase.g").c_str(), p.g);
      break;
    case MediumPhase::Kind::Tabulated:
      out << name << ".moments exact for the interpolant\n";  // before: Gauss-Legendre, 512 nodes
      // Absent before order 2 took the matrix by parts (the tables of that time are rebuilt).
      out << name << ".order 2 by parts " << DirectionQuadrature::kPatchRows << " x "
          << DirectionQuadrature::kPatchColumns << '\n';
      write_array(out, (name + ".matrix.mu").c_str(), p.matrix->mu());
      for (int i = 0; i < p.matrix->wavelengths(); ++i) {
        write_array(out, (name + ".matrix.a1").c_str(), p.matrix->a1()[static_cast<size_t>(i)]);
        write_array(out, (name + ".matrix.b1").c_str(), p.matrix->b1()[static_cast<size_t>(i)]);
      }
      break;
  }
}

}  // namespace

std::string ScatteringTablesKey::file_name() const {
  char name[40];
  std::snprintf(name, sizeof name, "orders-%016llx.bin", static_cast<unsigned long long>(hash));
  return name;
}

ScatteringTablesKey scattering_tables_key(const AtmosphereModel& atm, const SunColumnTable::Resolution& sun_table,
                                          const MultipleScatteringSettings& ms) {
  std::ostringstream out;
  out << std::scientific << std::setprecision(kKeySignificantDigits - 1);
  out << "format " << kScatteringTablesFormat << '\n';
  out << "planet_radius_m " << atm.planet_radius_m() << "\ntop_radius_m " << atm.top_radius_m() << '\n';
  write_array(out, "wavelengths_nm", atm.grid().nanometres());
  for (const Medium& m : atm.media()) write_medium(out, m);
  write_array(out, "ground.albedo", atm.ground_albedo());
  out << "sun_table " << sun_table.n_r << ' ' << sun_table.n_mu << ' ' << sun_table.segments << '\n';
  out << "orders " << ms.orders << "\naltitude_samples " << ms.altitude_samples << "\nsun_samples " << ms.sun_samples
      << "\nview_segments " << ms.view_segments << "\nangular_degree " << ms.angular_degree << '\n';
  if (ms.polarisation) out << "polarisation 1\n";  // absent for scalar tables (their keys stay as they were)
  // Absent where nothing is cut (the keys of tables without a tabulated matrix stay as they were).
  if (ScatteringOrders::cuts_forward_peaks(atm, ms)) out << "forward_cone_deg " << ms.forward_cone_deg << '\n';
  for (int k = 2; k <= ms.orders; ++k) {
    const DirectionQuadrature q = ScatteringOrders::quadrature_of_order(ms.angular_degree, k, ms.quadrature_refinement);
    out << "order " << k << " degree " << ScatteringOrders::degree_of_order(ms.angular_degree, k) << " segments "
        << ScatteringOrders::segments_of_order(ms, k) << " directions " << q.sky_zenith_nodes << ' '
        << q.ground_zenith_nodes << ' ' << q.azimuth_nodes << " horizon panels " << q.sky_horizon_nodes << ' '
        << q.ground_horizon_nodes << ' ' << DirectionQuadrature::kHorizonPanelWidth << '\n';
  }
  ScatteringTablesKey key;
  key.inputs = out.str();
  key.hash = fnv1a64(key.inputs);
  return key;
}

}  // namespace skyspec
