#include "render/scene_tables.hpp"

namespace skyspec {

SunColumnTable::Resolution sun_table_resolution(const Scene& s) {
  return SunColumnTable::Resolution{s.render.table_altitude_samples, s.render.table_zenith_samples, 64};
}

MultipleScatteringSettings multiple_scattering_settings(const Scene& s) {
  MultipleScatteringSettings ms;
  ms.orders = s.render.scattering_orders;
  ms.altitude_samples = s.render.ms_altitude_samples;
  ms.sun_samples = s.render.ms_sun_samples;
  ms.angular_degree = s.render.ms_angular_degree;
  ms.view_segments = s.render.ms_view_segments;
  ms.higher_order_segments = s.render.ms_higher_order_segments;
  ms.forward_cone_deg = s.render.ms_forward_cone_deg;
  ms.polarisation = s.output.polarisation && ms.orders >= 2;
  return ms;
}

ScatteringTablesKey scattering_tables_key(const Scene& s) {
  const AtmosphereModel atmosphere(s.atmosphere, make_wavelength_grid(s), s.render.cache_tables);
  return scattering_tables_key(atmosphere, sun_table_resolution(s), multiple_scattering_settings(s));
}

}  // namespace skyspec
