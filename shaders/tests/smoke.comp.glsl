#version 460
// Vulkan smoke test: out[i] = 2 in[i] + 1.
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) readonly buffer In { float inValues[]; };
layout(set = 0, binding = 1) writeonly buffer Out { float outValues[]; };
layout(push_constant) uniform Push { uint count; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < count) {
        outValues[i] = 2.0 * inValues[i] + 1.0;
    }
}
