// The field probes of the unit tests (tests/unit/shaders/test_*_probe.comp): a field's device words and points
// in its grid space go in, (found, value) per point comes out, as the tracking kernels find the field there.
// Every probe kernel takes the words', the points' (vec4 each) and the results' (vec2 each) device addresses
// and the point count first in its push constants, then whatever `extra` holds; its workgroups are 64 wide.
#pragma once

#include "core/vk/Buffer.h"
#include "core/vk/ComputePipeline.h"
#include "tests/support/TestContext.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

namespace ripple::test {

template <class Extra>
std::vector<glm::vec2> runProbe(std::span<const uint32_t> spirv, const std::string& name, const std::vector<uint32_t>& words,
                                const std::vector<glm::vec4>& gridPoints, const Extra& extra) {
    const vk::Context& context = testContext();
    struct Params {
        uint64_t words, points, results;
        uint32_t count;
        Extra extra;
    };
    const vk::ComputePipeline kernel(context, spirv, name, sizeof(Params));
    vk::Buffer field(context, words.size() * 4, name + " field"), in(context, gridPoints.size() * 16, name + " points"),
        out(context, gridPoints.size() * 8, name + " results");
    field.upload(words.data(), words.size() * 4);
    in.upload(gridPoints.data(), gridPoints.size() * 16);
    const Params params{field.address(), in.address(), out.address(), uint32_t(gridPoints.size()), extra};
    context.submitAndWait([&](VkCommandBuffer cmd) {
        vk::computeBarrier(cmd);
        kernel.bind(cmd);
        kernel.pushConstants(cmd, &params, sizeof params);
        kernel.dispatch(cmd, (uint32_t(gridPoints.size()) + 63) / 64);
    });
    std::vector<glm::vec2> results(gridPoints.size());
    out.download(results.data(), results.size() * 8);
    return results;
}

}  // namespace ripple::test
