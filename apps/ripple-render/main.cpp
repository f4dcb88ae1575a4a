// ripple-render: renders a glTF file, a volume file (raw or NRRD) or a built-in demo scene to a PNG (or JPEG,
// PFM, EXR) through any ANARI library. This file parses the command line, makes every rank agree on it under
// mpirun and reports what stops the run; Render.cpp renders.
#include "apps/ripple-render/ListDevices.h"
#include "apps/ripple-render/Options.h"
#include "apps/ripple-render/Render.h"
#include "mpi/Communicator.h"
#include "mpi/Runtime.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

int main(int argc, char** argv) {
    // --time counts from here: loading the library and the scene are part of the run it bounds.
    const auto processStart = std::chrono::steady_clock::now();
    // Under mpirun every rank runs this program on its share of the scene (data-parallel ANARI).
    ripple::mpi::Runtime runtime(&argc, &argv);
    // Made before anything can fail: duplicating the communicator is collective.
    const ripple::mpi::Communicator ranks = ripple::mpi::Communicator::world();
    using ripple::apps::Options;
    Options options;
    CLI::App app{"ripple-render: render a glTF 2.0 file, a volume file or a built-in demo scene through an ANARI library"};
    ripple::apps::addRenderOptions(app, options);
    int parseOutcome = 0;  // 0: parsed; else the parser's exit code + 1
    std::optional<CLI::ParseError> parseError;
    try {
        app.parse(argc, argv);
        options.sppGiven = app.count("--spp") > 0;
    } catch (const CLI::ParseError& e) {
        parseError = e;
        parseOutcome = e.get_exit_code() + 1;
    }
    if (ranks.distributed()) {
        const std::string why = ripple::apps::optionsDisagreement(ranks, ripple::apps::agreedOptions(options, parseOutcome));
        if (!why.empty()) {
            if (ranks.rank() == 0) std::fprintf(stderr, "[ripple-render] ERROR: %s\n", why.c_str());
            return 1;
        }
    }
    if (parseError) {
        // Every rank parsed the same arguments and reached the same verdict; one rank speaks.
        return ranks.rank() == 0 ? app.exit(*parseError) : (parseError->get_exit_code() == 0 ? 0 : 1);
    }

    // It lives here, outside the error handler: under mpirun a failing rank must end every rank before its
    // device is released, since that release is collective and the other ranks would never join it.
    ripple::apps::Session session;
    try {
        if (options.listDevices) return ripple::apps::listDevices(options, ranks, session);
        ripple::apps::TimeBudget budget(options.seconds, processStart);
        if (options.field.listFields) {
            if (ranks.rank() == 0) ripple::apps::printVolumeFields(options.field);
            return 0;
        }
        ripple::apps::applyViewState(options, app);
        return ripple::apps::render(options, ranks, session, budget);
    } catch (const std::exception& e) {
        // Other ranks may wait for this one in a collective call (the device's release among them): end
        // them all, before this rank's session is released, never hang.
        if (ranks.distributed()) ranks.abort(std::string("ripple-render: ") + e.what());
        std::fprintf(stderr, "[ripple-render] ERROR: %s\n", e.what());
        return 1;
    }
}
