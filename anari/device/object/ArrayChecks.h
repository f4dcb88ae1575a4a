// The one way objects check their data at commit: NaN/Inf in arrays and float parameters, indices out of
// range, and elements of the wrong type. One pass over the data; a problem comes back as the message that
// names the parameter, what is wrong, where (the first bad element) and how many, for Object::invalidate.
#pragma once

#include "anari/anari.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace ripple::device {

// NaN or infinite components in `values` (vectors read from an array, the columns of a matrix, or one
// vector): "parameter 'vertex.position' is not finite: element 2 holds NaN; 3 of 10 elements hold NaN or
// Inf". `element` names one entry ("element", "texel", "column"). nullopt when all are finite.
std::optional<std::string> nonFiniteProblem(std::string_view parameter, std::span<const glm::vec4> values,
                                            std::string_view element = "element");
std::optional<std::string> nonFiniteProblem(std::string_view parameter, float value);
std::optional<std::string> nonFiniteProblem(std::string_view parameter, const glm::vec3& value);
std::optional<std::string> nonFiniteProblem(std::string_view parameter, const glm::vec4& value);
std::optional<std::string> nonFiniteProblem(std::string_view parameter, const glm::mat4& value);

// Flattened indices (`components` per element, as readIndices gives them) of which one is `limit` or more:
// "parameter 'primitive.index' element 4 refers to vertex 7, but there are 3 vertices; 2 of 5 elements
// are out of range". A negative index arrives as UINT64_MAX and is named as such. nullopt when all fit.
std::optional<std::string> indexProblem(std::string_view parameter, std::span<const uint64_t> indices, int components,
                                        uint64_t limit, std::string_view target = "vertex",
                                        std::string_view targets = "vertices");

// "parameter 'vertex.color' has elements of type ANARI_STRING, expected <expected>".
std::string elementTypeProblem(std::string_view parameter, ANARIDataType given, std::string_view expected);

}  // namespace ripple::device
