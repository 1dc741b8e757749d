#include "mbd_stage/euler_parameters.h"

#include <gtest/gtest.h>

using namespace clearjoint::mbd;

TEST(EulerParameters, RotationMatrixIsOrthonormalAndMatchesAxisAngle)
{
  const Vector3 axis = Vector3(0.3, -0.5, 0.8).normalized();
  const double angle = 1.234;  // rad
  const Matrix3 A = rotation_matrix(euler_parameters_from_axis_angle(axis, angle));
  // 1e-14: a handful of roundings of O(1) numbers.
  EXPECT_LT((A * A.transpose() - Matrix3::Identity()).norm(), 1e-14);
  EXPECT_NEAR(A.determinant(), 1.0, 1e-14);
  const Matrix3 ref = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  EXPECT_LT((A - ref).norm(), 1e-14);
  const Vector4 e = euler_parameters_from_rotation(A);
  EXPECT_LT((rotation_matrix(e) - A).norm(), 1e-14);
}

TEST(EulerParameters, RateIsTangentAndMatchesFiniteDifference)
{
  const Vector4 e = euler_parameters_from_axis_angle(Vector3(1, 2, 3), 0.7);
  const Vector3 w_B(0.4, -1.1, 2.5);  // rad/s
  const Vector4 de = euler_parameter_rate(e, w_B);
  // d‖e‖²/dt = 2 e·ė = 0 exactly (kinematics keep the norm).
  EXPECT_NEAR(e.dot(de), 0.0, 1e-15);
  // A(t+h) ≈ A(t)·exp(h ω̃'): compare ė with the finite difference of the exact rotation.
  const double h = 1e-6;  // s; central difference error O(h²) ~ 1e-12
  const Matrix3 A = rotation_matrix(e);
  const Matrix3 Ap = A * Eigen::AngleAxisd(h * w_B.norm(), w_B.normalized()).toRotationMatrix();
  const Matrix3 Am = A * Eigen::AngleAxisd(-h * w_B.norm(), w_B.normalized()).toRotationMatrix();
  Vector4 ep = euler_parameters_from_rotation(Ap), em = euler_parameters_from_rotation(Am);
  if (ep.dot(e) < 0) ep = -ep;
  if (em.dot(e) < 0) em = -em;
  EXPECT_LT(((ep - em) / (2 * h) - de).norm(), 1e-8);
}
