// The model's material laws (fe_stage/material/material_law.h): the elastic law's stress and
// tangent against Hooke's law in closed form, and J2Law against the J2 return map it wraps —
// the same stress, tangent, history and energies through the interface the FE model uses.
#include "fe_stage/material/j2_law.h"
#include "fe_stage/scene.h"

#include <gtest/gtest.h>

using namespace clearjoint::fe;
using namespace clearjoint::fe::detail;
using dealii::SymmetricTensor;

namespace
{
  SymmetricTensor<2, 3> strain(double a, double b, double c, double d, double e, double f)
  {
    SymmetricTensor<2, 3> eps;
    eps[0][0] = a, eps[1][1] = b, eps[2][2] = c, eps[1][2] = d, eps[0][2] = e, eps[0][1] = f;
    return eps;
  }
} // namespace

TEST(MaterialLaw, ElasticLawIsHookesLawWithoutHistory)
{
  FeScene scene;  // steel: E = 210 GPa, ν = 0.3
  const auto law = make_material(scene, false);
  EXPECT_FALSE(law->has_history());
  const double E = scene.material.E, nu = scene.material.nu;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const SymmetricTensor<2, 3> eps = strain(1e-3, -2e-4, 5e-4, 3e-4, -1e-4, 2e-4);
  const MaterialResponse r = law->evaluate(0, eps);
  EXPECT_TRUE(r.converged);
  EXPECT_FALSE(r.yielding);
  const SymmetricTensor<2, 3> hooke =
    lambda * trace(eps) * dealii::unit_symmetric_tensor<3>() + 2 * mu * eps;
  EXPECT_LE((r.stress - hooke).norm(), 1e-12 * hooke.norm());
  EXPECT_LE((law->elastic_tangent() * eps - hooke).norm(), 1e-12 * hooke.norm());
  EXPECT_NEAR(law->elastic_energy(0, eps), 0.5 * (hooke * eps), 1e-12 * (hooke * eps));
  EXPECT_EQ(law->equivalent_plastic_strain(0), 0.0);
}

TEST(MaterialLaw, J2LawIsTheReturnMapWithItsHistory)
{
  FeScene scene;  // the SPEC hardening table (yield at 250 MPa)
  const auto law = make_material(scene, true);
  ASSERT_TRUE(law->has_history());
  law->resize(2);
  J2Plasticity reference(scene.material.E, scene.material.nu,
                         hardening_table(scene.material, ""));
  J2History h;
  // a strain far beyond yield (≈ 1.5 σ_y/E in shear), then a second step from the committed state
  for (const double scale : {1.0, 1.6})
    {
      const SymmetricTensor<2, 3> eps = strain(3e-3, -1e-3, -1e-3, 2e-3, 0.0, 1e-3) * scale;
      Eigen::Matrix3d e;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          e(i, j) = eps[i][j];
      const J2Response ref = reference.evaluate(e, h);
      const MaterialResponse r = law->evaluate(1, eps);
      ASSERT_TRUE(r.converged);
      ASSERT_TRUE(ref.plastic);
      EXPECT_TRUE(r.yielding);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          EXPECT_DOUBLE_EQ(r.stress[i][j], ref.stress(i, j));
      for (int I = 0; I < 6; ++I)
        for (int J = 0; J < 6; ++J)
          EXPECT_DOUBLE_EQ(r.tangent[voigt_index[I][0]][voigt_index[I][1]][voigt_index[J][0]]
                                    [voigt_index[J][1]],
                           ref.tangent(I, J));
      EXPECT_DOUBLE_EQ(r.plastic_work, ref.plastic_work);
      EXPECT_DOUBLE_EQ(law->equivalent_plastic_strain(1, true), h.trial.alpha);
      EXPECT_EQ(law->equivalent_plastic_strain(1), scale == 1.0 ? 0.0 : h.committed.alpha);
      law->commit(1);
      h.commit();
      EXPECT_DOUBLE_EQ(law->equivalent_plastic_strain(1), h.committed.alpha);
      EXPECT_DOUBLE_EQ(law->elastic_energy(1, eps), reference.elastic_energy(e, h.committed));
    }
  // the other point kept its virgin state
  EXPECT_EQ(law->equivalent_plastic_strain(0), 0.0);
}
