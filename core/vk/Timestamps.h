// GPU timestamps: a query pool of `capacity` stamps, written with write() inside a command buffer and read
// back as seconds after the submission finished.
#pragma once

#include "core/vk/Context.h"

#include <vector>

namespace ripple::vk {

class Timestamps {
public:
    Timestamps(const Context& context, uint32_t capacity);
    ~Timestamps();
    Timestamps(const Timestamps&) = delete;
    Timestamps& operator=(const Timestamps&) = delete;

    void reset(VkCommandBuffer cmd);
    void write(VkCommandBuffer cmd, uint32_t index);
    // Seconds between stamps `from` and `to` of the last finished submission.
    double seconds(uint32_t from, uint32_t to) const;
    // Stamps 0 .. count-1 of the last finished submission, in seconds after stamp 0 (one query).
    std::vector<double> read(uint32_t count) const;
    uint32_t capacity() const { return capacity_; }

private:
    const Context& context_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    uint32_t capacity_ = 0;
};

}  // namespace ripple::vk
