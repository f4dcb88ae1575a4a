// The apps' --size option: "WIDTHxHEIGHT", each side 1 to 16384 pixels (ANARI frames past that are
// refused by Ripple anyway). One parser, so every tool accepts and refuses the same sizes alike.
#pragma once

#include <glm/glm.hpp>

#include <regex>
#include <stdexcept>
#include <string>

namespace ripple::apps {

// Throws std::runtime_error naming the option and what is wrong.
inline glm::uvec2 parseImageSize(const std::string& text) {
    static const std::regex pattern(R"((\d{1,5})x(\d{1,5}))");
    std::smatch m;
    if (!std::regex_match(text, m, pattern)) throw std::runtime_error("--size '" + text + "' is not WIDTHxHEIGHT");
    const glm::uvec2 size(std::stoul(m[1]), std::stoul(m[2]));
    if (size.x == 0 || size.y == 0 || size.x > 16384 || size.y > 16384)
        throw std::runtime_error("--size " + text + ": each side must be 1 to 16384 pixels");
    return size;
}

}  // namespace ripple::apps
