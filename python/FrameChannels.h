// A frame from Python: render() renders and waits (as pynari's does), get(channel) returns any channel as
// a numpy array of the channel's shape and dtype.
#pragma once

#include "python/ObjectHandle.h"

namespace ripple::python {

class Frame : public Object {
public:
    Frame(std::shared_ptr<DeviceSession> session, ANARIObject handle);
    void render();
    // (height, width) for one-component channels, else (height, width, components); rows bottom-up, as
    // ANARI maps them. A copy: the mapping ends before get returns.
    py::array get(const std::string& channel);
    uint64_t map(const std::string& channel);  // pynari's raw pointer, for code that reads it itself
    void unmap(const std::string& channel);
};

}  // namespace ripple::python
