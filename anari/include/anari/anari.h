/* The ANARI 1.0 C API: handles, callback types and the 46 core functions plus the extension entry point.
   Usable from C and C++; the loader (libanari.so) defines every function and forwards to a device library. */
#pragma once

#include <stddef.h>
#include <stdint.h>

#include "anari_enums.h"

/* Functions the loader exports even when built with -fvisibility=hidden. */
#ifndef ANARI_INTERFACE
#if defined(_WIN32)
#define ANARI_INTERFACE __declspec(dllimport)
#else
#define ANARI_INTERFACE __attribute__((visibility("default")))
#endif
#endif

#define ANARI_INVALID_HANDLE 0

/* Handles are opaque pointers. In C++ each is a distinct struct type, and the inheritance lets an
   ANARIArray1D or ANARIGeometry pass where an ANARIObject is expected, as with the Khronos header. C has
   no inheritance, so there every handle is a plain void pointer. */
#ifdef __cplusplus
struct _ANARILibrary {};
struct _ANARIObject {};
struct _ANARIDevice : _ANARIObject {};
struct _ANARIArray : _ANARIObject {};
struct _ANARIArray1D : _ANARIArray {};
struct _ANARIArray2D : _ANARIArray {};
struct _ANARIArray3D : _ANARIArray {};
struct _ANARICamera : _ANARIObject {};
struct _ANARIFrame : _ANARIObject {};
struct _ANARIGeometry : _ANARIObject {};
struct _ANARIGroup : _ANARIObject {};
struct _ANARIInstance : _ANARIObject {};
struct _ANARILight : _ANARIObject {};
struct _ANARIMaterial : _ANARIObject {};
struct _ANARIRenderer : _ANARIObject {};
struct _ANARISampler : _ANARIObject {};
struct _ANARISpatialField : _ANARIObject {};
struct _ANARISurface : _ANARIObject {};
struct _ANARIVolume : _ANARIObject {};
struct _ANARIWorld : _ANARIObject {};

typedef struct _ANARILibrary* ANARILibrary;
typedef struct _ANARIObject* ANARIObject;
typedef struct _ANARIDevice* ANARIDevice;
typedef struct _ANARIArray* ANARIArray;
typedef struct _ANARIArray1D* ANARIArray1D;
typedef struct _ANARIArray2D* ANARIArray2D;
typedef struct _ANARIArray3D* ANARIArray3D;
typedef struct _ANARICamera* ANARICamera;
typedef struct _ANARIFrame* ANARIFrame;
typedef struct _ANARIGeometry* ANARIGeometry;
typedef struct _ANARIGroup* ANARIGroup;
typedef struct _ANARIInstance* ANARIInstance;
typedef struct _ANARILight* ANARILight;
typedef struct _ANARIMaterial* ANARIMaterial;
typedef struct _ANARIRenderer* ANARIRenderer;
typedef struct _ANARISampler* ANARISampler;
typedef struct _ANARISpatialField* ANARISpatialField;
typedef struct _ANARISurface* ANARISurface;
typedef struct _ANARIVolume* ANARIVolume;
typedef struct _ANARIWorld* ANARIWorld;
#else
typedef void* ANARILibrary;
typedef void* ANARIObject;
typedef void* ANARIDevice;
typedef void* ANARIArray;
typedef void* ANARIArray1D;
typedef void* ANARIArray2D;
typedef void* ANARIArray3D;
typedef void* ANARICamera;
typedef void* ANARIFrame;
typedef void* ANARIGeometry;
typedef void* ANARIGroup;
typedef void* ANARIInstance;
typedef void* ANARILight;
typedef void* ANARIMaterial;
typedef void* ANARIRenderer;
typedef void* ANARISampler;
typedef void* ANARISpatialField;
typedef void* ANARISurface;
typedef void* ANARIVolume;
typedef void* ANARIWorld;
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  const char* name;
  ANARIDataType type;
} ANARIParameter;

/* Passed as an array ended by an entry whose name is NULL. */
typedef struct {
  const char* name;
  ANARIDataType type;
  const void* value;
} ANARIParameterValue;

typedef void (*ANARIMemoryDeleter)(const void* userPtr, const void* appMemory);
typedef void (*ANARIStatusCallback)(const void* userPtr, ANARIDevice device, ANARIObject source,
                                    ANARIDataType sourceType, ANARIStatusSeverity severity,
                                    ANARIStatusCode code, const char* message);
typedef void (*ANARIFrameCompletionCallback)(const void* userPtr, ANARIDevice device, ANARIFrame frame);

/* Libraries and devices */
ANARI_INTERFACE ANARILibrary anariLoadLibrary(const char* name, ANARIStatusCallback statusCallback,
                                              const void* statusCallbackUserData);
ANARI_INTERFACE void anariUnloadLibrary(ANARILibrary library);
ANARI_INTERFACE void anariLoadModule(ANARILibrary library, const char* name);
ANARI_INTERFACE void anariUnloadModule(ANARILibrary library, const char* name);
ANARI_INTERFACE ANARIDevice anariNewDevice(ANARILibrary library, const char* type);
ANARI_INTERFACE ANARIDevice anariNewInitializedDevice(ANARILibrary library, const char* type,
                                                      ANARIParameterValue* initializers);
ANARI_INTERFACE const char** anariGetDeviceSubtypes(ANARILibrary library);
ANARI_INTERFACE const char** anariGetDeviceExtensions(ANARILibrary library, const char* deviceSubtype);

/* Arrays */
ANARI_INTERFACE ANARIArray1D anariNewArray1D(ANARIDevice device, const void* appMemory, ANARIMemoryDeleter deleter,
                                             const void* userData, ANARIDataType dataType, uint64_t numElements1);
ANARI_INTERFACE ANARIArray2D anariNewArray2D(ANARIDevice device, const void* appMemory, ANARIMemoryDeleter deleter,
                                             const void* userData, ANARIDataType dataType, uint64_t numElements1,
                                             uint64_t numElements2);
ANARI_INTERFACE ANARIArray3D anariNewArray3D(ANARIDevice device, const void* appMemory, ANARIMemoryDeleter deleter,
                                             const void* userData, ANARIDataType dataType, uint64_t numElements1,
                                             uint64_t numElements2, uint64_t numElements3);
ANARI_INTERFACE void* anariMapArray(ANARIDevice device, ANARIArray array);
ANARI_INTERFACE void anariUnmapArray(ANARIDevice device, ANARIArray array);

/* Objects */
ANARI_INTERFACE ANARILight anariNewLight(ANARIDevice device, const char* type);
ANARI_INTERFACE ANARICamera anariNewCamera(ANARIDevice device, const char* type);
ANARI_INTERFACE ANARIGeometry anariNewGeometry(ANARIDevice device, const char* type);
ANARI_INTERFACE ANARISpatialField anariNewSpatialField(ANARIDevice device, const char* type);
ANARI_INTERFACE ANARIVolume anariNewVolume(ANARIDevice device, const char* type);
ANARI_INTERFACE ANARISurface anariNewSurface(ANARIDevice device);
ANARI_INTERFACE ANARIMaterial anariNewMaterial(ANARIDevice device, const char* type);
ANARI_INTERFACE ANARISampler anariNewSampler(ANARIDevice device, const char* type);
ANARI_INTERFACE ANARIGroup anariNewGroup(ANARIDevice device);
ANARI_INTERFACE ANARIInstance anariNewInstance(ANARIDevice device, const char* type);
ANARI_INTERFACE ANARIWorld anariNewWorld(ANARIDevice device);
ANARI_INTERFACE ANARIRenderer anariNewRenderer(ANARIDevice device, const char* type);
ANARI_INTERFACE ANARIFrame anariNewFrame(ANARIDevice device);
ANARI_INTERFACE ANARIObject anariNewObject(ANARIDevice device, const char* objectType, const char* type);

/* Parameters and object lifetime */
ANARI_INTERFACE void anariSetParameter(ANARIDevice device, ANARIObject object, const char* name,
                                       ANARIDataType dataType, const void* mem);
ANARI_INTERFACE void anariUnsetParameter(ANARIDevice device, ANARIObject object, const char* name);
ANARI_INTERFACE void anariUnsetAllParameters(ANARIDevice device, ANARIObject object);
ANARI_INTERFACE void* anariMapParameterArray1D(ANARIDevice device, ANARIObject object, const char* name,
                                               ANARIDataType dataType, uint64_t numElements1,
                                               uint64_t* elementStride);
ANARI_INTERFACE void* anariMapParameterArray2D(ANARIDevice device, ANARIObject object, const char* name,
                                               ANARIDataType dataType, uint64_t numElements1,
                                               uint64_t numElements2, uint64_t* elementStride);
ANARI_INTERFACE void* anariMapParameterArray3D(ANARIDevice device, ANARIObject object, const char* name,
                                               ANARIDataType dataType, uint64_t numElements1,
                                               uint64_t numElements2, uint64_t numElements3,
                                               uint64_t* elementStride);
ANARI_INTERFACE void anariUnmapParameterArray(ANARIDevice device, ANARIObject object, const char* name);
ANARI_INTERFACE void anariCommitParameters(ANARIDevice device, ANARIObject object);
ANARI_INTERFACE void anariRelease(ANARIDevice device, ANARIObject object);
ANARI_INTERFACE void anariRetain(ANARIDevice device, ANARIObject object);

/* Introspection and properties */
ANARI_INTERFACE const char** anariGetObjectSubtypes(ANARIDevice device, ANARIDataType objectType);
ANARI_INTERFACE const void* anariGetObjectInfo(ANARIDevice device, ANARIDataType objectType,
                                               const char* objectSubtype, const char* infoName,
                                               ANARIDataType infoType);
ANARI_INTERFACE const void* anariGetParameterInfo(ANARIDevice device, ANARIDataType objectType,
                                                  const char* objectSubtype, const char* parameterName,
                                                  ANARIDataType parameterType, const char* infoName,
                                                  ANARIDataType infoType);
/* Returns 1 when the property was written to mem, 0 otherwise. */
ANARI_INTERFACE int anariGetProperty(ANARIDevice device, ANARIObject object, const char* name, ANARIDataType type,
                                     void* mem, uint64_t size, ANARIWaitMask mask);

/* Frames. Mapped rows start at the bottom of the image. */
ANARI_INTERFACE const void* anariMapFrame(ANARIDevice device, ANARIFrame frame, const char* channel,
                                          uint32_t* width, uint32_t* height, ANARIDataType* pixelType);
ANARI_INTERFACE void anariUnmapFrame(ANARIDevice device, ANARIFrame frame, const char* channel);
ANARI_INTERFACE void anariRenderFrame(ANARIDevice device, ANARIFrame frame);
ANARI_INTERFACE int anariFrameReady(ANARIDevice device, ANARIFrame frame, ANARIWaitMask mask);
ANARI_INTERFACE void anariDiscardFrame(ANARIDevice device, ANARIFrame frame);

/* Extension interface: a device's extra function by name, NULL when it has none of that name; cast the
   result to the function's own type. */
ANARI_INTERFACE void (*anariDeviceGetProcAddress(ANARIDevice device, const char* name))(void);

#ifdef __cplusplus
} /* extern "C" */
#endif
