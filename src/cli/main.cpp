// skyspec command-line front end: parses and validates, then calls the library.
//
// Exit codes: 0 success; 2 bad input (unknown option or key, value out of range, ...);
// 3 an input or output file could not be read or written; 1 an internal error;
// 130 / 143 stopped by SIGINT / SIGTERM (interrupt.hpp), leaving no partial file.

#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "interrupt.hpp"
#include "skyspec/error.hpp"
#include "skyspec/version.hpp"

int main(int argc, char** argv) {
  using namespace skyspec::cli;
  CLI::App app{"skyspec: a spectral, physically based sky simulator.\n"
               "Renders the sky from Rayleigh scattering derived from the refractive index of air and\n"
               "aerosol (Mie) scattering, one ray march per spectral sample, into spectral OpenEXR."};
  app.set_version_flag("--version", std::string("skyspec ") + skyspec::version_string());
  app.require_subcommand(1);

  const std::vector<Command> commands = {
      add_render_command(app),
      add_convert_command(app),
      add_compare_command(app),
      add_irradiance_command(app),
      add_timelapse_command(app),
      add_aerial_command(app),
      add_coefficients_command(app),
  };

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::string which;
    for (const auto& c : commands)
      if (c.app->parsed()) which = c.app->get_name() + " ";
    std::cerr << "skyspec: error: " << e.what() << "\n(see `skyspec " << which << "--help`)\n";
    return kExitBadInput;
  }

  install_interrupt_handlers();
  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
  } catch (const Interrupted& e) {
    std::cerr << "skyspec: " << e.what() << "\n";
    return e.exit_code();
  } catch (const skyspec::InputError& e) {
    std::cerr << "skyspec: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const skyspec::IoError& e) {
    std::cerr << "skyspec: error: " << e.what() << "\n";
    return kExitIo;
  } catch (const std::exception& e) {
    std::cerr << "skyspec: internal error: " << e.what() << "\n";
    return kExitInternal;
  }
  return kExitOk;
}
