#pragma once
/// \file
/// \brief iris::geometry — closed triangle meshes for test scenes (CGAL-free header).
///
/// Every builder returns counter-clockwise triangles seen from outside (outward normals
/// (v1 − v0) × (v2 − v0)); all but `make_quad` are closed 2-manifolds.

#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "iris/render/scene.hpp"

namespace iris::geometry {

/// \brief The core's mesh type: positions and outward CCW index triples.
using triangle_mesh = iris::triangle_mesh;

class error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// \brief Axis-aligned box [min, max]. \throws error if any extent is not positive.
triangle_mesh make_box(glm::vec3 min, glm::vec3 max);
/// \brief Cube of edge `edge` centred at `centre`.
triangle_mesh make_cube(glm::vec3 centre, float edge);
/// \brief Triangular prism: an equilateral triangle of side `side` in the xy plane
/// (one vertex pointing +y), centred at `centre`, extruded by `depth` along z.
triangle_mesh make_prism(glm::vec3 centre, float side, float depth);
/// \brief Hollow cube: outer cube minus a concentric inner cube (inner walls face inwards,
/// into the cavity). \pre 0 < inner_edge < outer_edge.
triangle_mesh make_hollow_cube(glm::vec3 centre, float outer_edge, float inner_edge);
/// \brief An open rectangle (two triangles) centred at `centre` spanned by `u` and `v`
/// (full edge vectors); its normal is u × v. Not closed: emitters, floors, screens.
triangle_mesh make_quad(glm::vec3 centre, glm::vec3 u, glm::vec3 v);

/// \brief Translate · rotate (degrees, applied about x, then y, then z) · scale.
glm::mat4 make_transform(glm::vec3 translate, glm::vec3 rotate_degrees_xyz, glm::vec3 scale);
/// \brief The mesh with every position transformed (orientation kept when det > 0, and
/// restored by flipping the triangles when det < 0).
triangle_mesh transformed(const triangle_mesh& m, const glm::mat4& t);
/// \brief Total surface area.
double surface_area(const triangle_mesh& m);

}  // namespace iris::geometry
