#include "app.hpp"

#include <ostream>
#include <string>

#include "interrupt.hpp"
#include "setting_spellings.hpp"
#include "skyspec/error.hpp"
#include "skyspec/version.hpp"

namespace skyspec::cli {

CliApp::CliApp()
    : app{"skyspec: a spectral, physically based sky simulator.\n"
          "Renders the sky from Rayleigh scattering derived from the refractive index of air and\n"
          "aerosol (Mie) scattering, one ray march per spectral sample, into spectral OpenEXR."} {
  app.set_version_flag("--version", std::string("skyspec ") + skyspec::version_string());
  app.require_subcommand(1);
  commands = {
      add_render_command(app),       add_convert_command(app),   add_compare_command(app),
      add_irradiance_command(app),   add_timelapse_command(app), add_aerial_command(app),
      add_coefficients_command(app), add_job_command(app),       add_merge_command(app),
      add_reference_command(app),    add_lee_command(app),       add_view_command(app),
  };
}

int run_cli(int argc, const char* const* argv, CliMode mode, std::ostream& out, std::ostream& err) {
  CliApp cli;
  try {
    cli.app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return cli.app.exit(e, out, err);
  } catch (const CLI::CallForAllHelp& e) {
    return cli.app.exit(e, out, err);
  } catch (const CLI::CallForVersion& e) {
    return cli.app.exit(e, out, err);
  } catch (const CLI::ParseError& e) {
    std::string which;
    for (const auto& c : cli.commands)
      if (c.app->parsed()) which = c.app->get_name() + " ";
    err << "skyspec: error: " << e.what() << "\n(see `skyspec " << which << "--help`)\n";
    return kExitBadInput;
  }

  if (mode == CliMode::Run) install_interrupt_handlers();
  try {
    for (const auto& c : cli.commands) {
      if (!c.app->parsed()) continue;
      if (mode == CliMode::Run) return c.run();
      if (c.validate) c.validate();
      return kExitOk;
    }
  } catch (const Interrupted& e) {
    err << "skyspec: " << e.what() << "\n";
    return e.exit_code();
  } catch (const skyspec::InputError& e) {
    err << "skyspec: error: " << in_cli_words(e).what() << "\n";
    return kExitBadInput;
  } catch (const skyspec::IoError& e) {
    err << "skyspec: error: " << e.what() << "\n";
    return kExitIo;
  } catch (const std::exception& e) {
    err << "skyspec: internal error: " << e.what() << "\n";
    return kExitInternal;
  }
  return kExitOk;
}

}  // namespace skyspec::cli
