#include "core/drag.h"

#include <glm/gtc/type_ptr.hpp>
#include <glm/matrix.hpp>

namespace drape {

ScreenMapping make_screen_mapping(const drape_view& v, const glm::dvec3& origin) {
    ScreenMapping m;
    glm::dmat4 world(glm::make_mat4(v.world));
    world[3] += world * glm::dvec4(origin, 0.0);  // world * translate(origin)
    const glm::dmat4 view(glm::make_mat4(v.view));
    const glm::dmat4 proj(glm::make_mat4(v.projection));
    m.mvp = proj * view * world;
    m.inv_mvp = glm::inverse(m.mvp);
    m.viewport = glm::dvec2(v.viewport[0], v.viewport[1]);
    return m;
}

bool to_screen(const ScreenMapping& m, const glm::vec3& x, glm::dvec2* px, double* ndc_z) {
    const glm::dvec4 clip = m.mvp * glm::dvec4(glm::dvec3(x), 1.0);
    if (!(clip.w > 0)) return false;
    const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
    *px = (glm::dvec2(ndc) * 0.5 + 0.5) * m.viewport;
    *ndc_z = ndc.z;
    return true;
}

glm::dvec3 from_screen(const ScreenMapping& m, const glm::dvec2& px, double ndc_z) {
    const glm::dvec2 ndc = px / m.viewport * 2.0 - 1.0;
    const glm::dvec4 p = m.inv_mvp * glm::dvec4(ndc, ndc_z, 1.0);
    return glm::dvec3(p) / p.w;
}

}  // namespace drape
