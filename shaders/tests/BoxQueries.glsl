// The queries of the closed-box crease tests (tests/core/bundle/ClosedBoxCreaseTest.cpp): per item a
// point and a normal of either sign in, its answer (and for walks the distance to what it found,
// after the count's answers) out.
struct BoxQuery {
    vec4 position;
    vec4 normal;
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer BoxQueries { BoxQuery queries[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer BoxAnswers { uint answers[]; };
