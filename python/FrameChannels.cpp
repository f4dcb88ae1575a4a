// Rendering a frame and reading its channels into numpy arrays.
#include "python/FrameChannels.h"

#include <cstring>

namespace ripple::python {

Frame::Frame(std::shared_ptr<DeviceSession> s, ANARIObject h) : Object(std::move(s), h, ANARI_FRAME, "") {
    // pynari's frames start with an 8-bit sRGB colour channel; scripts may set another.
    const ANARIDataType color = ANARI_UFIXED8_RGBA_SRGB;
    anariSetParameter(session_->handle(), handle_, "channel.color", ANARI_DATA_TYPE, &color);
}

void Frame::render() {
    const ANARIDevice d = session_->handle();
    const auto frame = static_cast<ANARIFrame>(handle());
    {
        // The device may call back (status, array deleters) from its threads meanwhile; and under MPI the
        // other ranks' Python threads must not wait on this one's GIL.
        py::gil_scoped_release released;
        anariRenderFrame(d, frame);
        anariFrameReady(d, frame, ANARI_WAIT);
    }
    session_->raiseStatus("frame.render()");
}

py::array Frame::get(const std::string& channel) {
    const ANARIDevice d = session_->handle();
    const auto frame = static_cast<ANARIFrame>(handle());
    uint32_t width = 0, height = 0;
    ANARIDataType pixelType = ANARI_UNKNOWN;
    const void* pixels = anariMapFrame(d, frame, channel.c_str(), &width, &height, &pixelType);
    const std::string what = "frame.get('" + channel + "')";
    if (pixels == nullptr) {
        session_->raiseStatus(what);
        throw py::value_error(what + ": the frame has no such channel (set it, e.g. frame.setParameter('" + channel +
                              "', anari.DATA_TYPE, anari.FLOAT32), commit and render first)");
    }
    const std::optional<ElementFormat> format = elementFormat(pixelType);
    if (!format) {
        anariUnmapFrame(d, frame, channel.c_str());
        throw py::value_error(what + ": pixels of type " + shortTypeName(pixelType) + " have no numpy form");
    }
    std::vector<py::ssize_t> shape = {py::ssize_t(height), py::ssize_t(width)};
    if (format->components > 1) shape.push_back(py::ssize_t(format->components));
    py::array result(componentDtype(*format), shape);
    std::memcpy(result.mutable_data(), pixels, size_t(width) * height * format->components * format->bytes);
    anariUnmapFrame(d, frame, channel.c_str());
    session_->raiseStatus(what);
    return result;
}

uint64_t Frame::map(const std::string& channel) {
    uint32_t width = 0, height = 0;
    ANARIDataType pixelType = ANARI_UNKNOWN;
    const void* pixels = anariMapFrame(session_->handle(), static_cast<ANARIFrame>(handle()), channel.c_str(),
                                       &width, &height, &pixelType);
    session_->raiseStatus("frame.map('" + channel + "')");
    return uint64_t(reinterpret_cast<uintptr_t>(pixels));
}

void Frame::unmap(const std::string& channel) {
    anariUnmapFrame(session_->handle(), static_cast<ANARIFrame>(handle()), channel.c_str());
    session_->raiseStatus("frame.unmap('" + channel + "')");
}

}  // namespace ripple::python
