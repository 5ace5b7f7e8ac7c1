// The queries of the closed-box crease tests (tests/core/bundle/ClosedBoxCreaseTest.cpp): per item a
// point and a normal of either sign in, its answer (and for walks the distance to what it found,
// after the count's answers) out.
struct BoxQuery {
    vec4 position;
    vec4 normal;
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer BoxQueries { BoxQuery queries[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer BoxAnswers { uint answers[]; };

// The push constants both tests share (after the walk's pool view). centreOnly: x's own pixel
// alone, without the contact taps (the tests' mutation).
struct BoxQueryPush {
    uvec2 queries;
    uvec2 results;
    uint count;
    uint centreOnly;
};

// This invocation's query (point x, normal n); false past the count.
bool blBoxQuery(BoxQueryPush box, out vec3 x, out vec3 n) {
    uint item = gl_GlobalInvocationID.x;
    if (item >= box.count) {
        return false;
    }
    BoxQuery q = BoxQueries(box.queries).queries[item];
    x = q.position.xyz;
    n = q.normal.xyz;
    return true;
}
