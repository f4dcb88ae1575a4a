// The pass-through compositing device: forwards every ANARI call to a wrapped device that renders only
// this rank's share of the world, and composites all ranks' color and depth into rank 0's frame.
#pragma once

#include "anari/backend/DeviceInterface.h"
#include "anari/backend/LibraryInterface.h"
#include "anari/ptc/WrappedLibrary.h"
#include "mpi/Compositor.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace ripple::ptc {

class PtcDevice final : public abi::DeviceInterface {
public:
    PtcDevice(ANARIStatusCallback defaultCallback, const void* defaultCallbackUserPtr);
    ~PtcDevice() override;

    ANARIDevice handle() { return abi::handleFromDevice(this); }

    RIPPLE_ANARI_DEVICE_OVERRIDES  // every ANARI device call (anari/backend/DeviceInterface.h)

private:
    // What the application asked of a frame; the wrapped frame always renders FLOAT32_VEC4 color and
    // FLOAT32 depth, which this side converts after compositing.
    struct FrameState {
        uint32_t width = 0, height = 0;
        ANARIDataType colorType = ANARI_UNKNOWN, depthType = ANARI_UNKNOWN;
        std::shared_ptr<const void> communicatorHandle;  // a copy of the application's MPI_Comm
        std::unique_ptr<mpi::Compositor> compositor;
        mpi::CompositeMethod compositeMethod = mpi::CompositeMethod::Auto;  // what compositor was made with
        std::vector<uint8_t> mappedColor;  // the composited color in colorType
        int references = 1;                // the application's, mirrored: the state lives as long as the frame
        ANARIObject renderer = nullptr;
    };

    bool isDevice(ANARIObject object) const {
        return static_cast<const void*>(object) == static_cast<const abi::DeviceInterface*>(this);
    }
    // Loads the wrapped library and creates its device on first use; null (reported once) if it cannot.
    abi::DeviceInterface* wrapped();
    ANARIDevice wrappedHandle() const { return abi::handleFromDevice(wrapped_); }
    void loadWrapped();
    void setDeviceParameter(const char* name, ANARIDataType dataType, const void* mem);
    void setFrameParameter(FrameState& frame, ANARIFrame handle, const char* name, ANARIDataType dataType,
                           const void* mem);
    void report(ANARIStatusSeverity severity, const std::string& message) const;

    ANARIStatusCallback callback_;
    const void* callbackUserPtr_;
    std::string libraryName_;
    mpi::CompositeMethod compositeMethod_ = mpi::CompositeMethod::Auto;  // the device parameter "compositing"
    std::shared_ptr<const void> communicatorHandle_;  // a copy of the application's MPI_Comm
    // Device parameters set before the wrapped device exists, replayed when it is created.
    struct PendingParameter {
        std::string name;
        ANARIDataType type;
        std::vector<uint8_t> bytes;
        std::string text;
    };
    std::vector<PendingParameter> pending_;
    WrappedLibrary library_;
    abi::DeviceInterface* wrapped_ = nullptr;
    bool loadFailed_ = false;
    int references_ = 1;
    std::map<ANARIFrame, FrameState> frames_;
    // The alpha of each renderer's "background": where it is 0, a pixel at infinite depth with some alpha is
    // the coverage of a surface its latest sample missed (an edge), not background, and must be composited.
    std::map<ANARIObject, float> backgroundAlpha_;
};

}  // namespace ripple::ptc
