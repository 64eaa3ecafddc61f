#include "stages/lighting.hpp"

#include <cmath>

namespace passim {
namespace {

// The spec's "u ⊙ v" = max(u·v, 0).
double dot_clamped(const Vec3& a, const Vec3& b) {
  double d = glm::dot(a, b);
  return d > 0.0 ? d : 0.0;
}

Vec3 unit(const Vec3& v) {
  double len = std::sqrt(glm::dot(v, v));
  return len > 0.0 ? v / len : v;
}

}  // namespace

LitColor light_vertex(const LightingState& L, const Material& m, const Vec4& eye, const Vec3& n) {
  // c = e_cm + a_cm·a_cs + Σ att_i·spot_i·[a_cm·a_cli + (n⊙VP_pli)·d_cm·d_cli + f_i·(n⊙ĥ_i)^s_rm·s_cm·s_cli]
  const Vec3 v = Vec3(eye) / eye.w;
  Vec3 rgb = Vec3(m.emission) + Vec3(m.ambient) * Vec3(L.model_ambient);
  Vec3 specular_sum(0.0);
  for (const Light& light : L.lights) {
    if (!light.enabled) continue;
    Vec3 vp;  // vector from the vertex to the light
    double attenuation = 1.0;
    if (light.position.w != 0.0) {
      Vec3 p = Vec3(light.position) / light.position.w;
      vp = p - v;
      double d = std::sqrt(glm::dot(vp, vp));
      attenuation = 1.0 / (light.constant_attenuation + light.linear_attenuation * d +
                           light.quadratic_attenuation * d * d);
      if (d > 0.0) vp = vp / d;  // unit(vp), with the length already computed
    } else {
      vp = unit(Vec3(light.position));
    }
    double spot = 1.0;
    if (light.spot_cutoff != 180.0) {
      double c = glm::dot(-vp, unit(light.spot_direction));
      spot = c >= std::cos(light.spot_cutoff * (M_PI / 180.0)) ? std::pow(c > 0.0 ? c : 0.0, light.spot_exponent)
                                                                 : 0.0;
    }
    const double n_dot_vp = dot_clamped(n, vp);
    Vec3 term = Vec3(m.ambient) * Vec3(light.ambient) + n_dot_vp * Vec3(m.diffuse) * Vec3(light.diffuse);
    Vec3 spec(0.0);
    if (glm::dot(n, vp) != 0.0) {  // f_i
      Vec3 h = vp + (L.local_viewer ? unit(-v) : Vec3(0.0, 0.0, 1.0));
      double n_dot_h = dot_clamped(n, unit(h));
      // pow(x, 0) is 1 for every x (C11 7.12.7.4), so the call is skipped then: same bits.
      const double power = m.shininess == 0.0 ? 1.0 : std::pow(n_dot_h, m.shininess);
      spec = power * Vec3(m.specular) * Vec3(light.specular);
    }
    const double k = attenuation * spot;
    rgb += k * term;
    specular_sum += k * spec;
  }
  LitColor out;
  if (L.color_control == GL_SEPARATE_SPECULAR_COLOR) {
    out.secondary = specular_sum;
  } else {
    rgb += specular_sum;
    out.secondary = Vec3(0.0);
  }
  out.primary = Vec4(rgb, m.diffuse.a);  // alpha is the material's diffuse alpha
  return out;
}

}  // namespace passim
