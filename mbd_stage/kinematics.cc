#include "mbd_stage/kinematics.h"

#include <stdexcept>

namespace clearjoint::mbd
{
  KinVec body_vector(const KinematicsView &k, const int body, const Vector3 &a_B)
  {
    const BodyKinematics &b = k[body];
    KinVec x;
    x.value = b.A * a_B;
    if (body == ground_index)
      return x;
    x.rate = b.A * b.w_B.cross(a_B);                  // d(A a')/dt = A (ω' × a')
    x.quad = b.A * b.w_B.cross(b.w_B.cross(a_B));     // A ω̃'ω̃' a'
    x.slots[0].body = body;
    x.slots[0].J_w = -b.A * skew(a_B);                // A (ω̇' × a') = −A ã' ω̇'
    x.n_slots = 1;
    return x;
  }

  KinVec body_point(const KinematicsView &k, const int body, const Vector3 &s_B)
  {
    KinVec x = body_vector(k, body, s_B);
    const BodyKinematics &b = k[body];
    x.value += b.r;
    if (body == ground_index)
      return x;
    x.rate += b.v;
    x.slots[0].J_v = Matrix3::Identity();
    return x;
  }

  KinVec operator-(const KinVec &a, const KinVec &b)
  {
    KinVec x = a;
    x.value -= b.value;
    x.rate -= b.rate;
    x.quad -= b.quad;
    for (int i = 0; i < b.n_slots; ++i)
    {
      const KinSlot &s = b.slots[i];
      int j = 0;
      while (j < x.n_slots && x.slots[j].body != s.body)
        ++j;
      if (j == x.n_slots)
      {
        if (x.n_slots == 2)
          throw std::logic_error("KinVec: more than two bodies in one expression");
        x.slots[j].body = s.body;
        x.slots[j].J_v.setZero();
        x.slots[j].J_w.setZero();
        ++x.n_slots;
      }
      x.slots[j].J_v -= s.J_v;
      x.slots[j].J_w -= s.J_w;
    }
    return x;
  }

  KinScalar dot(const KinVec &a, const KinVec &b, const int n_bodies)
  {
    KinScalar s;
    s.value = a.value.dot(b.value);
    s.rate = a.rate.dot(b.value) + a.value.dot(b.rate);
    s.quad = a.quad.dot(b.value) + 2.0 * a.rate.dot(b.rate) + a.value.dot(b.quad);
    s.row = Eigen::RowVectorXd::Zero(6 * n_bodies);
    for (int i = 0; i < a.n_slots; ++i)
    {
      const int c = 6 * a.slots[i].body;
      s.row.segment<3>(c) += b.value.transpose() * a.slots[i].J_v;
      s.row.segment<3>(c + 3) += b.value.transpose() * a.slots[i].J_w;
    }
    for (int i = 0; i < b.n_slots; ++i)
    {
      const int c = 6 * b.slots[i].body;
      s.row.segment<3>(c) += a.value.transpose() * b.slots[i].J_v;
      s.row.segment<3>(c + 3) += a.value.transpose() * b.slots[i].J_w;
    }
    return s;
  }

  KinScalar component(const KinVec &a, const int axis, const int n_bodies)
  {
    KinScalar s;
    s.value = a.value[axis];
    s.rate = a.rate[axis];
    s.quad = a.quad[axis];
    s.row = Eigen::RowVectorXd::Zero(6 * n_bodies);
    for (int i = 0; i < a.n_slots; ++i)
    {
      const int c = 6 * a.slots[i].body;
      s.row.segment<3>(c) += a.slots[i].J_v.row(axis);
      s.row.segment<3>(c + 3) += a.slots[i].J_w.row(axis);
    }
    return s;
  }
} // namespace clearjoint::mbd
