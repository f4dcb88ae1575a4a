// The message of the std::invalid_argument a call throws: how the tests of checked inputs (unstructured
// meshes, NanoVDB buffers) compare a refusal with the words it must say.
#pragma once

#include <stdexcept>
#include <string>

namespace ripple::test {

// The message `call()` throws as std::invalid_argument; empty when it throws nothing.
template <class Call>
std::string refusalOf(Call call) {
    try {
        call();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

}  // namespace ripple::test
