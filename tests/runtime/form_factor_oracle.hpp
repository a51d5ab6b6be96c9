#pragma once
// The unoccluded irradiance a floor point gets from a wall rectangle, by the
// midpoint rule: the oracle the radiosity tests hold the gather's E to where
// a radius cuts the rectangle and no closed form fits.
#include <glm/glm.hpp>

#include <cmath>

namespace deepgi::test {

// The integral of cos_x cos_y / d^2 over the rectangle x in `x_range`, y in
// `y_range` of the plane at depth z (normal +z, towards the point), seen from
// the floor point p (normal +y), over the parts within `radius` of p and in
// front of both surfaces: E per unit radiance, on nx by ny cells.
inline double floor_from_wall_form_factor(glm::vec3 p, float radius, glm::dvec2 x_range,
                                          glm::dvec2 y_range, double z, int nx, int ny) {
    const double width = x_range.y - x_range.x, height = y_range.y - y_range.x;
    const double cell = (width / nx) * (height / ny);
    double sum = 0.0;
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            const glm::dvec3 y(x_range.x + width * (i + 0.5) / nx,
                               y_range.x + height * (j + 0.5) / ny, z);
            const glm::dvec3 v = y - glm::dvec3(p);
            const double dd = glm::dot(v, v);
            if (dd >= double(radius) * radius) continue;
            const double d = std::sqrt(dd);
            const double cos_x = v.y / d, cos_y = -v.z / d;
            if (cos_x <= 0.0 || cos_y <= 0.0) continue;
            sum += cos_x * cos_y / dd * cell;
        }
    }
    return sum;
}

}  // namespace deepgi::test
