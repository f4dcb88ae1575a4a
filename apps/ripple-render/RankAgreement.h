// ripple-render under mpirun: every rank must be given the same command line (file or --demo, --spp,
// --size, --time...). One collective check at start-up names the first option the ranks disagree on, so
// that no rank renders alone or waits for a peer that took another path.
#pragma once

#include "mpi/Communicator.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace ripple::apps {

struct AgreedOption {
    std::string name;       // as the user writes it: "--spp", "the scene (file or --demo)"
    uint64_t value = 0;     // the number itself, or a hash of the text
    bool numeric = false;   // value is a count worth printing (smallest and largest over ranks)
};

// A hash of `text` that is the same on every rank (64-bit FNV-1a).
uint64_t optionHash(std::string_view text);

// Collective (one allreduce): empty when every rank holds the same values, else a message naming the first
// option that differs. Every rank gets the same message.
std::string optionsDisagreement(const mpi::Communicator& ranks, const std::vector<AgreedOption>& options);

}  // namespace ripple::apps
