#include "fe_stage/material/j2_law.h"

#include "fe_stage/material/hardening_table.h"
#include "fe_stage/scene.h"

namespace clearjoint::fe::detail
{
  namespace
  {
    using dealii::SymmetricTensor;

    Eigen::Matrix3d to_eigen(const SymmetricTensor<2, 3> &e)
    {
      Eigen::Matrix3d m;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          m(i, j) = e[i][j];
      return m;
    }

    SymmetricTensor<2, 3> to_deal(const Eigen::Matrix3d &m)
    {
      SymmetricTensor<2, 3> e;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          e[i][j] = 0.5 * (m(i, j) + m(j, i));
      return e;
    }

    /// The Voigt 6×6 (material/j2_plasticity.h's layout) as a 4th-order tensor, no factors.
    SymmetricTensor<4, 3> to_deal(const Matrix6 &C)
    {
      SymmetricTensor<4, 3> t;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i; j < 3; ++j)
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = k; l < 3; ++l)
              t[i][j][k][l] = C(voigt_of(i, j), voigt_of(k, l));
      return t;
    }
  }  // namespace

  J2Law::J2Law(J2Plasticity law, const LinearElastic &elastic)
    : law_(std::move(law))
    , elastic_(elastic)
    , elastic_tangent_(to_deal(law_.elastic_tangent()))
  {}

  void J2Law::resize(const std::size_t n_points) { history_.assign(n_points, J2History()); }

  MaterialResponse J2Law::evaluate(const std::size_t point, const SymmetricTensor<2, 3> &eps)
  {
    const J2Response r = law_.evaluate(to_eigen(eps), history_[point]);
    MaterialResponse m;
    m.converged = r.status.converged;
    if (!m.converged)
      return m;
    m.stress = to_deal(r.stress);
    m.yielding = r.plastic;
    m.plastic_work = r.plastic_work;
    if (r.plastic)
      m.tangent = to_deal(r.tangent);
    return m;
  }

  SymmetricTensor<2, 3> J2Law::plastic_strain(const std::size_t point, const bool trial) const
  {
    const J2History &h = history_[point];
    return to_deal(trial ? h.trial.eps_p : h.committed.eps_p);
  }

  double J2Law::equivalent_plastic_strain(const std::size_t point, const bool trial) const
  {
    const J2History &h = history_[point];
    return trial ? h.trial.alpha : h.committed.alpha;
  }

  double J2Law::elastic_energy(const std::size_t point, const SymmetricTensor<2, 3> &eps) const
  {
    return law_.elastic_energy(to_eigen(eps), history_[point].committed);
  }

  std::unique_ptr<MaterialLaw> make_material(const FeScene &scene, const bool elastoplastic)
  {
    const LinearElastic elastic =
      LinearElastic::from_young_poisson(scene.material.E, scene.material.nu);
    if (!elastoplastic)
      return std::make_unique<ElasticLaw>(elastic);
    return std::make_unique<J2Law>(J2Plasticity(scene.material.E, scene.material.nu,
                                                hardening_table(scene.material, scene.source_file),
                                                "material", scene.source_file),
                                   elastic);
  }
}  // namespace clearjoint::fe::detail
