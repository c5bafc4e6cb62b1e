// The outside of every Photon program: errors become one line on stderr naming the program, and an
// exit code (0 success, 2 bad input, 1 runtime failure); command-line errors are bad input.
#pragma once

#include <csignal>
#include <cstdio>
#include <exception>
#include <new>

#include <CLI/CLI.hpp>

#include "core/system/error.h"

namespace photon {

template <typename Run>
int runProgram(const char* name, Run run) {
    // A file-size limit (ulimit -f) or a closed pipe make writes fail with a reason, not the
    // process die with a signal.
    std::signal(SIGXFSZ, SIG_IGN);
    std::signal(SIGPIPE, SIG_IGN);
    auto report = [&](const char* what) { std::fprintf(stderr, "%s: %s\n", name, printable(what).c_str()); };
    try {
        return run();
    } catch (const InputError& e) {
        report(e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        report("out of memory");
        return 1;
    } catch (const std::exception& e) {
        report(e.what());
        return 1;
    }
}

// A boolean option and its --no- form ("--quiet,-q" also takes --no-quiet), the last one given
// counting: every flag of every program can be turned back off, as the README says.
inline CLI::Option* addSwitch(CLI::App& app, const std::string& names, bool& value, const std::string& help) {
    std::string longName = names.substr(0, names.find(','));
    return app.add_flag(names + ",!--no-" + longName.substr(2), value, help)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
}

// A file or folder option: an empty name (`-o ''`) is refused by the option's name, not met later
// as a file without a name.
inline const CLI::Validator kFileName{[](std::string& name) { return name.empty() ? std::string("an empty file name") : std::string(); },
                                      "FILE"};

// --backend: one of auto|cpu|cuda|vulkan, or a comma-separated list of them (one device each).
inline const CLI::Validator kBackendList{
    [](std::string& list) {
        std::size_t start = 0;
        for (;;) {
            std::size_t comma = list.find(',', start);
            std::string one = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
            if (one != "auto" && one != "cpu" && one != "cuda" && one != "vulkan") {
                return "'" + one + "' is not a backend (auto|cpu|cuda|vulkan, or a list such as cpu,cpu)";
            }
            if (comma == std::string::npos) {
                return std::string();
            }
            start = comma + 1;
        }
    },
    "BACKEND[,BACKEND...]"};

// Parses the command line: --help prints the help and returns 0; a bad command line throws
// InputError with CLI11's one-line reason; otherwise returns -1 (go on).
inline int parseCommandLine(CLI::App& app, int argc, char** argv) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        throw InputError(e.what());
    }
    return -1;
}

}  // namespace photon
