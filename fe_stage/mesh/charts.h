// Manifolds of the generated meshes: the Hertz indenter's profile and the polar chart on which the
// bearing and the journal place their nodes on common rays. deal.II; header-only.
#pragma once

#include "fe_stage/core/dim.h"
#include "fe_stage/mesh/journal_pose.h"
#include <deal.II/base/numbers.h>

#include <deal.II/base/point.h>
#include <deal.II/grid/manifold.h>

#include <cmath>
#include <memory>

namespace clearjoint::fe::detail
{

  /// The deformable Hertz indenter: (x, η, z) ↦ (x, η + cap(r)·(1 − η/H), z), r = √(x²+z²),
  /// a block of height H whose bottom is cap(r) = p/(1 + p/c), p = r²/2R — Hertz's profile
  /// near the contact (at the contact radius a ≈ 0.3 mm it differs from r²/2R by p/c ≈ 5e-4
  /// relative) that levels off far away, so the block stays a block (c = H/2).
  class IndenterChart : public ChartManifold<dim, dim, dim>
  {
  public:
    IndenterChart(const double R, const double H)
      : R_(R)
      , H_(H)
    {}
    double cap(const double x, const double z) const
    {
      const double p = (x * x + z * z) / (2.0 * R_);
      return p / (1.0 + p / (0.5 * H_));
    }
    Point<dim> pull_back(const Point<dim> &X) const override
    {
      const double c = cap(X[0], X[2]);
      return Point<dim>(X[0], (X[1] - c) / (1.0 - c / H_), X[2]);
    }
    Point<dim> push_forward(const Point<dim> &c) const override
    {
      return Point<dim>(c[0], c[1] + cap(c[0], c[2]) * (1.0 - c[1] / H_), c[2]);
    }
    std::unique_ptr<Manifold<dim, dim>> clone() const override
    {
      return std::make_unique<IndenterChart>(R_, H_);
    }

  private:
    double R_, H_;
  };

  /// Polar chart about the bearing axis (z): (φ, s, z) ↦ s·ρ(φ)·(sin φ, −cos φ) + z e_z, with φ
  /// measured from −y. For the bearing ρ ≡ 1 (s is the radius); for the journal, whose axis is
  /// offset to y = −c_r, ρ(φ) is the distance from the bearing axis to the journal's surface
  /// along the ray at φ, so s = 1 is the journal surface. Both bodies thus refine and place
  /// their surface nodes on the same rays: the bearing's and the journal's contact nodes pair
  /// up exactly (node-to-node along the bearing's normal) at every refinement level.
  class RayChart : public ChartManifold<dim, dim, dim>
  {
  public:
    RayChart(const double c_r, const double R_J, const bool journal)
      : ChartManifold<dim, dim, dim>(Tensor<1, dim>({2.0 * numbers::PI, 0.0, 0.0}))
      , c_r_(c_r)
      , R_J_(R_J)
      , journal_(journal)
    {}
    double rho(const double phi) const
    {
      if (!journal_)
        return 1.0;
      const double s = std::sin(phi), c = std::cos(phi);
      return c_r_ * c + std::sqrt(R_J_ * R_J_ - c_r_ * c_r_ * s * s);
    }
    Point<dim> pull_back(const Point<dim> &X) const override
    {
      const double phi = std::atan2(X[0], -X[1]);
      return Point<dim>(phi, std::hypot(X[0], X[1]) / rho(phi), X[2]);
    }
    Point<dim> push_forward(const Point<dim> &c) const override
    {
      const double r = c[1] * rho(c[0]);
      return Point<dim>(r * std::sin(c[0]), -r * std::cos(c[0]), c[2]);
    }
    std::unique_ptr<Manifold<dim, dim>> clone() const override
    {
      return std::make_unique<RayChart>(c_r_, R_J_, journal_);
    }

  private:
    double c_r_, R_J_;
    bool journal_;
  };

  /// The journal's RayChart carried along with the journal's rigid placement (JournalPose): the
  /// tilted journal of the misalignment study refines onto its own, tilted, cylinder.
  class PlacedChart : public ChartManifold<dim, dim, dim>
  {
  public:
    PlacedChart(const RayChart &aligned, const JournalPose &pose)
      : ChartManifold<dim, dim, dim>(Tensor<1, dim>({2.0 * numbers::PI, 0.0, 0.0}))
      , aligned_(aligned)
      , pose_(pose)
    {}
    Point<dim> pull_back(const Point<dim> &X) const override
    {
      const auto l = pose_.to_local({X[0], X[1], X[2]});
      return aligned_.pull_back(Point<dim>(l[0], l[1], l[2]));
    }
    Point<dim> push_forward(const Point<dim> &c) const override
    {
      const Point<dim> l = aligned_.push_forward(c);
      const auto X = pose_.to_world({l[0], l[1], l[2]});
      return Point<dim>(X[0], X[1], X[2]);
    }
    std::unique_ptr<Manifold<dim, dim>> clone() const override
    {
      return std::make_unique<PlacedChart>(aligned_, pose_);
    }

  private:
    RayChart aligned_;
    JournalPose pose_;
  };
}  // namespace clearjoint::fe::detail
