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

void write_species(std::ostream& out, const char* name, const ScatteringSpecies& s) {
  out << name << ".profile " << s.profile.describe() << '\n';
  write_array(out, (std::string(name) + ".scattering_per_m").c_str(), s.scattering_per_m);
  write_array(out, (std::string(name) + ".extinction_per_m").c_str(), s.extinction_per_m);
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
  write_species(out, "rayleigh", atm.rayleigh());
  write_species(out, "mie", atm.mie());
  write_species(out, "ozone", atm.ozone());
  out << "mie.phase " << to_string(atm.mie_phase().model) << '\n';
  write_array(out, "mie.g", atm.mie_g());
  if (const TabulatedScatteringMatrix* m = atm.mie_matrix()) {  // absent otherwise (keys stay as they were)
    write_array(out, "mie.matrix.mu", m->mu());
    for (int i = 0; i < m->wavelengths(); ++i) {
      write_array(out, "mie.matrix.a1", m->a1()[static_cast<size_t>(i)]);
      write_array(out, "mie.matrix.b1", m->b1()[static_cast<size_t>(i)]);
    }
  }
  write_array(out, "ground.albedo", atm.ground_albedo());
  out << "sun_table " << sun_table.n_r << ' ' << sun_table.n_mu << ' ' << sun_table.segments << '\n';
  out << "orders " << ms.orders << "\naltitude_samples " << ms.altitude_samples << "\nsun_samples " << ms.sun_samples
      << "\nview_segments " << ms.view_segments << "\nangular_degree " << ms.angular_degree << '\n';
  if (ms.polarisation) out << "polarisation 1\n";  // absent for scalar tables (their keys stay as they were)
  for (int k = 2; k <= ms.orders; ++k) {
    const DirectionQuadrature q = ScatteringOrders::quadrature_of_order(ms.angular_degree, k, ms.quadrature_refinement);
    out << "order " << k << " degree " << ScatteringOrders::degree_of_order(ms.angular_degree, k) << " directions "
        << q.sky_zenith_nodes << ' ' << q.ground_zenith_nodes << ' ' << q.azimuth_nodes << '\n';
  }
  ScatteringTablesKey key;
  key.inputs = out.str();
  key.hash = fnv1a64(key.inputs);
  return key;
}

}  // namespace skyspec
