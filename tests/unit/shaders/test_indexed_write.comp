#version 460
// Writes one word at an index through a buffer device address, unchecked: the GPU-assisted validation test
// (tests/unit/vulkan_validation_test.cpp) aims it past its buffer's end to show the layer sees such a write.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

layout(local_size_x = 1) in;

layout(buffer_reference, std430, buffer_reference_align = 4) buffer Words {
    uint words[];
};

layout(push_constant) uniform Params {
    uint64_t address;
    uint index;
    uint value;
} params;

void main() {
    Words(params.address).words[params.index] = params.value;
}
