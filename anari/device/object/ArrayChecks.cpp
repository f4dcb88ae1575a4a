// Commit-time data checks shared by every object of the Ripple device (see ArrayChecks.h).
#include "anari/device/object/ArrayChecks.h"

#include "anari/anari_type_traits.hpp"

#include <cmath>
#include <cstdint>

namespace ripple::device {
namespace {

// "NaN", "+Inf" or "-Inf" for the first non-finite component of v; nullptr when all are finite.
const char* nonFiniteKind(const glm::vec4& v) {
    for (int c = 0; c < 4; ++c) {
        if (std::isnan(v[c])) return "NaN";
        if (std::isinf(v[c])) return v[c] > 0.0f ? "+Inf" : "-Inf";
    }
    return nullptr;
}

std::string quoted(std::string_view name) {
    // Appending, not "'" + std::string(name): GCC 12 at -O3 warns (-Wrestrict) on the latter falsely.
    std::string text = "'";
    text.append(name).append("'");
    return text;
}

std::string plural(std::string_view noun) {
    std::string text(noun);
    if (!text.empty() && text.back() == 'y') return text.substr(0, text.size() - 1).append("ies");
    return text.append("s");
}

}  // namespace

std::optional<std::string> nonFiniteProblem(std::string_view parameter, std::span<const glm::vec4> values,
                                            std::string_view element) {
    size_t first = 0;
    uint64_t count = 0;
    const char* firstKind = nullptr;
    for (size_t i = 0; i < values.size(); ++i) {
        const char* kind = nonFiniteKind(values[i]);
        if (!kind) continue;
        if (count++ == 0) {
            first = i;
            firstKind = kind;
        }
    }
    if (count == 0) return std::nullopt;
    std::string message = "parameter " + quoted(parameter) + " is not finite: ";
    if (values.size() == 1) return message.append("it holds ").append(firstKind);
    message.append(element).append(" ").append(std::to_string(first)).append(" holds ").append(firstKind);
    message.append("; ").append(std::to_string(count)).append(" of ").append(std::to_string(values.size()));
    return message.append(" ").append(plural(element)).append(" hold NaN or Inf");
}

std::optional<std::string> nonFiniteProblem(std::string_view parameter, float value) {
    return nonFiniteProblem(parameter, glm::vec4(value, 0.0f, 0.0f, 0.0f));
}

std::optional<std::string> nonFiniteProblem(std::string_view parameter, const glm::vec3& value) {
    return nonFiniteProblem(parameter, glm::vec4(value, 0.0f));
}

std::optional<std::string> nonFiniteProblem(std::string_view parameter, const glm::vec4& value) {
    return nonFiniteProblem(parameter, std::span<const glm::vec4>(&value, 1));
}

std::optional<std::string> nonFiniteProblem(std::string_view parameter, const glm::mat4& value) {
    return nonFiniteProblem(parameter, std::span<const glm::vec4>(&value[0], 4), "column");
}

std::optional<std::string> indexProblem(std::string_view parameter, std::span<const uint64_t> indices, int components,
                                        uint64_t limit, std::string_view target, std::string_view targets) {
    const size_t width = size_t(components > 0 ? components : 1);
    const size_t elements = indices.size() / width;
    size_t firstElement = 0;
    uint64_t firstValue = 0, count = 0;
    for (size_t e = 0; e < elements; ++e) {
        for (size_t c = 0; c < width; ++c) {
            const uint64_t value = indices[e * width + c];
            if (value < limit) continue;
            if (count == 0) {
                firstElement = e;
                firstValue = value;
            }
            ++count;
            break;  // an element counts once, however many of its components are out of range
        }
    }
    if (count == 0) return std::nullopt;
    const std::string value = firstValue == UINT64_MAX ? std::string("-1 or below") : std::to_string(firstValue);
    std::string message = "parameter " + quoted(parameter) + " element " + std::to_string(firstElement) + " refers to ";
    message.append(target).append(" ").append(value).append(", but there are ");
    message.append(std::to_string(limit)).append(" ");
    message.append(targets).append("; ").append(std::to_string(count)).append(" of ");
    return message.append(std::to_string(elements)).append(" elements are out of range");
}

std::string elementTypeProblem(std::string_view parameter, ANARIDataType given, std::string_view expected) {
    std::string message = "parameter " + quoted(parameter) + " has elements of type " + ripple_anari::typeName(given);
    return message.append(", expected ").append(expected);
}

}  // namespace ripple::device
