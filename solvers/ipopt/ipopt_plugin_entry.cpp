// The Ipopt plugin's one exported symbol: its table of functions (ipopt_plugin.hpp). Everything
// else the plugin holds is hidden (linked with --exclude-libs,ALL).
#include "ipopt_plugin.hpp"
#include "ipopt_solve.hpp"

// Returns const void*, the type open_plugin() (plugins.cpp) calls it through: a call through a
// pointer to another function type is undefined (Clang's -fsanitize=function stops on it).
extern "C" __attribute__((visibility("default"))) const void* contactqp_ipopt_plugin() {
  static const contactqp::detail::IpoptPlugin table = [] {
    contactqp::detail::IpoptPlugin plugin;
    plugin.abi = contactqp::detail::kIpoptPluginAbi;
    plugin.check_options = &contactqp::detail::check_ipopt_options;
    plugin.solve = &contactqp::detail::solve_ipopt;
    return plugin;
  }();
  return &table;
}
