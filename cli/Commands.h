// Registration of the `vots` subcommands; each lives in its own file and owns its options.
#pragma once

namespace CLI {
class App;
}

namespace vots::cli {

void addFitCommand(CLI::App& app);    // FitCommand.cpp
void addInfoCommand(CLI::App& app);   // InfoCommand.cpp
void addVerifyCommand(CLI::App& app); // VerifyCommand.cpp
void addRenderCommand(CLI::App& app); // RenderCommand.cpp (only with the renderer)
void addServeCommand(CLI::App& app);  // ServeCommand.cpp (only with the server)

} // namespace vots::cli
