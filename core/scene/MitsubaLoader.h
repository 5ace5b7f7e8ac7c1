// Mitsuba 3 XML scenes, the subset a global-illumination scene uses, read into the scene model:
// <include>, <default> and $name parameters, <ref>/id (forward too, across includes); shapes obj,
// ply, rectangle, cube, disk, sphere (the last two tessellated, resolution stated) with to_world
// (translate, rotate, scale, matrix, lookat, composed in order), and shapegroup instances (copied); bsdfs diffuse (rgb or float
// reflectance, or a bitmap texture on obj/ply shapes) and twosided around one; emitters area (in a
// shape or by reference), point, spot (its edge profile mapped, the difference stated), constant
// and envmap (to_world a rotation about +y); a perspective sensor (fov, fov_axis
// x/y/smaller/larger/diagonal, to_world) with an hdrfilm's size. integrator, sampler and rfilter
// are not scene content and are ignored (said in the notes). Anything else is an error naming the
// file, the line and what is supported: never a silently different scene. How each element was
// mapped is kept in Scene::importNotes (`bundlelab info` prints them).
#pragma once

#include "scene/Scene.h"

#include <string>

namespace bl {

// Tessellation of Mitsuba's analytic shapes: a sphere of kMitsubaSphereSegments around by half as
// many from pole to pole, a disk of as many segments around.
inline constexpr int kMitsubaSphereSegments = 64;

Scene loadMitsubaScene(const std::string& path);

} // namespace bl
