// The `vots` command: subcommand registration and the one place that turns errors into exit codes.
#include "Args.h"
#include "Commands.h"

#include "vots/dist/Failure.h"
#include "vots/dist/mpi/MpiWorld.h"

#include <CLI/CLI.hpp>

#include <csignal>
#include <exception>
#include <iostream>

#ifndef VOTS_VERSION
#define VOTS_VERSION "unknown"
#endif

namespace {

using vots::dist::EXIT_BAD_INPUT;

int fail(int code, const std::string& message) {
    std::cerr << "vots: error: " << vots::cli::oneLine(message) << std::endl;
    return code;
}

} // namespace

int main(int argc, char** argv) {
    // A write past RLIMIT_FSIZE (a file-size quota) then fails with EFBIG, which every writer reports as
    // a one-line error; by default SIGXFSZ would kill `vots fit` or a running `vots serve` instead.
    std::signal(SIGXFSZ, SIG_IGN);
    CLI::App app{"vots " VOTS_VERSION
                 ": fit volumes into Vot-Spaces (Taylor polynomials in boxes), inspect and "
                 "verify them",
                 "vots"};
    app.set_version_flag("--version", VOTS_VERSION);
    app.require_subcommand(1);
    app.footer("Exit status: 0 success, 1 verification failed, 2 bad input. Run 'vots COMMAND --help' for a "
               "command's options.");
    vots::cli::addFitCommand(app);
    vots::cli::addInfoCommand(app);
    vots::cli::addVerifyCommand(app);
#ifdef VOTS_HAVE_RENDER
    vots::cli::addRenderCommand(app);
#endif
#ifdef VOTS_HAVE_SERVER
    vots::cli::addServeCommand(app);
#endif

    // CLI11 would report a mistyped command as "A subcommand is required"; name it instead.
    if (argc > 1 && argv[1][0] != '-') {
        const auto known = app.get_subcommands([&](CLI::App* sub) { return sub->check_name(argv[1]); });
        if (known.empty())
            return fail(EXIT_BAD_INPUT, std::string("unknown command '") + argv[1] + "' (try: vots --help)");
    }

    try {
        app.parse(argc, argv); // runs the chosen subcommand's callback
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::RuntimeError& e) {
        return e.get_exit_code(); // the command has already reported
    } catch (const vots::dist::ReportedOnRank0& e) {
        return e.exitCode(); // under mpirun rank 0 has reported the failure
    } catch (const CLI::ParseError& e) {
        return fail(EXIT_BAD_INPUT, e.what());
    } catch (...) {
        const std::exception_ptr failure = std::current_exception();
        return fail(vots::dist::exitCodeOf(vots::dist::failureKindOf(failure)),
                    vots::dist::failureTextOf(failure));
    }
    return 0;
}
