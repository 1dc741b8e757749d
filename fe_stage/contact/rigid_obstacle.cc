#include "fe_stage/contact/rigid_obstacle.h"

#include <cmath>

namespace clearjoint::fe
{
  namespace
  {
    // Component-wise arithmetic in the order deal.II's Tensor uses (a division is a product
    // with the reciprocal), so the gaps are bit-identical to the former deal.II version.
    double dot(const Vec3 &a, const Vec3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
    double norm(const Vec3 &a) { return std::sqrt(dot(a, a)); }
    Vec3 scaled(const double s, const Vec3 &a) { return {s * a[0], s * a[1], s * a[2]}; }
    Vec3 divided(const Vec3 &a, const double s) { return scaled(1.0 / s, a); }
    Vec3 minus(const Vec3 &a, const Vec3 &b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
    Vec3 plus(const Vec3 &a, const Vec3 &b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
  }  // namespace

  bool RigidObstacle::gap(const Vec3 &X, const double delta, double &g0, Vec3 &n) const
  {
    switch (kind)
      {
        case Kind::cylinder:
          {
            if (std::abs(X[2]) > half_length * (1.0 + 1e-10))
              return false;
            Vec3 C = {0.0, -offset - delta, X[2]};
            if (frame_angle != 0.0)
              {
                const double y = C[1];
                C[0] = std::sin(frame_angle) * y;  // R(−a)·(0, y) = (y sin a, y cos a)
                C[1] = std::cos(frame_angle) * y;
              }
            Vec3 d = minus(X, C);
            d[2] = 0.0;
            const double r = norm(d);
            n = divided(d, r);
            g0 = r - radius;
            return true;
          }
        case Kind::tilted_cylinder:
          {
            // Distance to the solid finite cylinder: along the side within its length,
            // beyond an end to the nearest rim point (outside the rim circle) or to the end
            // face (inside it). A point inside is measured to the side: the bearing's bore
            // is pushed radially by the journal, never through the journal's end face.
            const Vec3 a = {0.0, std::sin(tilt), std::cos(tilt)};
            const Vec3 C = {0.0, -offset - delta, 0.0};
            const Vec3 d = minus(X, C);
            const double s = dot(d, a);
            const Vec3 r = minus(d, scaled(s, a));
            const double rho = norm(r);
            const double beyond = std::abs(s) - half_length;
            if (beyond <= 0.0)
              {
                n = divided(r, rho);
                g0 = rho - radius;
              }
            else if (rho <= radius)
              {
                n = scaled(s > 0.0 ? 1.0 : -1.0, a);
                g0 = beyond;
              }
            else
              {
                const Vec3 rim =
                  plus(plus(C, scaled(std::copysign(half_length, s), a)), scaled(radius / rho, r));
                const Vec3 v = minus(X, rim);
                g0 = norm(v);
                n = divided(v, g0);
              }
            return true;
          }
        case Kind::sphere:
          {
            const Vec3 C = {0.0, radius - delta, 0.0};
            const Vec3 d = minus(X, C);
            const double r = norm(d);
            n = divided(d, r);
            g0 = r - radius;
            return true;
          }
        case Kind::plane:
          {
            n = {0.0, -1.0, 0.0};
            g0 = -delta - X[1];
            return true;
          }
      }
    return false;
  }
}  // namespace clearjoint::fe
