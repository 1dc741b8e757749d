#include "fe_stage/material/j2_law.h"

#include "fe_stage/material/hardening_table.h"
#include "fe_stage/scene.h"

#include <algorithm>
#include <vector>

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
    , finite_(law_)
    , elastic_(elastic)
    , elastic_tangent_(to_deal(law_.elastic_tangent()))
  {}

  void J2Law::resize(const std::size_t n_points) { history_.assign(n_points, J2History()); }

  /// Per point: the plastic strain's nine entries, then α.
  void J2Law::write_history(RestartWriter &out) const
  {
    std::vector<double> values;
    values.reserve(10 * history_.size());
    for (const auto &h : history_)
      {
        values.insert(values.end(), h.committed.eps_p.data(), h.committed.eps_p.data() + 9);
        values.push_back(h.committed.alpha);
      }
    out.put<std::uint64_t>(history_.size());
    out.put_vector(values);
  }

  void J2Law::read_history(RestartReader &in)
  {
    const auto n = in.get<std::uint64_t>();
    if (n != history_.size())
      in.damaged("its material history has " + std::to_string(n) + " points, this mesh " +
                 std::to_string(history_.size()));
    const std::vector<double> values = in.get_vector<double>();
    if (values.size() != 10 * n)
      in.damaged("its material history's values do not match its points");
    for (std::size_t p = 0; p < n; ++p)
      {
        J2State &s = history_[p].committed;
        std::copy(values.begin() + 10 * p, values.begin() + 10 * p + 9, s.eps_p.data());
        s.alpha = values[10 * p + 9];
        history_[p].trial = s;
      }
  }

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

  FiniteResponse J2Law::evaluate_finite(const std::size_t point, const dealii::Tensor<2, 3> &grad_u)
  {
    Eigen::Matrix3d H;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        H(i, j) = grad_u[i][j];
    const FiniteJ2Response r = finite_.evaluate_displacement_gradient(H, history_[point]);
    FiniteResponse m;
    m.converged = r.status.converged;
    if (!m.converged)
      {
        m.reason = r.status.reason;
        return m;
      }
    m.yielding = r.plastic;
    m.plastic_work = r.plastic_work;
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + H;
    const Eigen::Matrix3d &S = r.stress_pk2;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J = 0; J < 3; ++J)
        m.stress[i][J] = r.stress_pk1(i, J);
    // A_iJkL = δ_ik S_JL + Σ_IK F_iI ℂ_IJKL F_kK (ℂ = dS/dE_GL, minor-symmetric: the Voigt
    // entry of (I, J) and (K, L) with no factors); first G_IJkL = Σ_K ℂ_IJKL F_kK
    double G[3][3][3][3];
    for (unsigned int I = 0; I < 3; ++I)
      for (unsigned int J = 0; J < 3; ++J)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            {
              double g = 0.0;
              for (unsigned int K = 0; K < 3; ++K)
                g += r.tangent(voigt_of(I, J), voigt_of(K, L)) * F(k, K);
              G[I][J][k][L] = g;
            }
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J = 0; J < 3; ++J)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            {
              double a = i == k ? S(J, L) : 0.0;
              for (unsigned int I = 0; I < 3; ++I)
                a += F(i, I) * G[I][J][k][L];
              m.tangent[i][J][k][L] = a;
            }
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
