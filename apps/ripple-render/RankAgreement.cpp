// The start-up agreement check of ripple-render's options over ranks (see RankAgreement.h).
#include "apps/ripple-render/RankAgreement.h"

namespace ripple::apps {

uint64_t optionHash(std::string_view text) {
    uint64_t hash = 0xcbf29ce484222325ull;
    for (const char c : text) hash = (hash ^ uint8_t(c)) * 0x100000001b3ull;
    return hash;
}

std::string optionsDisagreement(const mpi::Communicator& ranks, const std::vector<AgreedOption>& options) {
    std::vector<uint64_t> values, lowest(options.size()), highest(options.size());
    for (const AgreedOption& option : options) values.push_back(option.value);
    ranks.minMax(values, lowest, highest);
    for (size_t i = 0; i < options.size(); ++i) {
        if (lowest[i] == highest[i]) continue;
        std::string message = "the ranks were given different " + options[i].name;
        if (options[i].numeric)
            message += " (from " + std::to_string(lowest[i]) + " to " + std::to_string(highest[i]) + ")";
        return message + ": every rank must be given the same options";
    }
    return {};
}

}  // namespace ripple::apps
