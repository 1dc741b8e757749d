// Dual-mortar coupling; see mortar.h for the contract and the references.
#include "fe_stage/contact/mortar.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace clearjoint::fe::mortar
{
  namespace
  {
    using Vec3 = Eigen::Vector3d;

    constexpr unsigned max_nodes = 9;

    /// Position index in {0, 1, ½} of each face node along a and b (deal.II's Q1/Q2 face
    /// order); the 4-node face uses the first four entries.
    constexpr unsigned pos_a[max_nodes] = {0, 1, 0, 1, 0, 1, 2, 2, 2};
    constexpr unsigned pos_b[max_nodes] = {0, 0, 1, 1, 2, 2, 0, 1, 2};

    /// Shape functions and their derivatives at one (a, b).
    struct Shape
    {
      unsigned n = 0;
      double N[max_nodes], Na[max_nodes], Nb[max_nodes];
    };

    /// 1-D Lagrange polynomials on the support points {0, 1, ½} (degree 2) or {0, 1}
    /// (degree 1), and their derivatives.
    void lagrange_1d(unsigned n_nodes, double t, double l[3], double dl[3])
    {
      if (n_nodes == 4)
        {
          l[0] = 1 - t, l[1] = t, l[2] = 0;
          dl[0] = -1, dl[1] = 1, dl[2] = 0;
        }
      else
        {
          l[0] = (1 - t) * (1 - 2 * t), l[1] = t * (2 * t - 1), l[2] = 4 * t * (1 - t);
          dl[0] = 4 * t - 3, dl[1] = 4 * t - 1, dl[2] = 4 - 8 * t;
        }
    }

    void eval_shape(unsigned n_nodes, double a, double b, Shape &s)
    {
      double la[3], dla[3], lb[3], dlb[3];
      lagrange_1d(n_nodes, a, la, dla);
      lagrange_1d(n_nodes, b, lb, dlb);
      s.n = n_nodes;
      for (unsigned k = 0; k < n_nodes; ++k)
        {
          s.N[k] = la[pos_a[k]] * lb[pos_b[k]];
          s.Na[k] = dla[pos_a[k]] * lb[pos_b[k]];
          s.Nb[k] = la[pos_a[k]] * dlb[pos_b[k]];
        }
    }

    /// Gauss–Legendre points and weights on [0, 1] (Newton on P_n from the Chebyshev guess).
    void gauss_legendre(unsigned n, std::vector<double> &x, std::vector<double> &w)
    {
      x.assign(n, 0.0);
      w.assign(n, 0.0);
      const double pi = 3.14159265358979323846;
      for (unsigned i = 0; i < n; ++i)
        {
          double z = std::cos(pi * (i + 0.75) / (n + 0.5)), dp = 1;
          for (int it = 0; it < 100; ++it)
            {
              double p0 = 1, p1 = z;  // P_0, P_1; recurrence up to P_n
              for (unsigned k = 2; k <= n; ++k)
                {
                  const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
                  p0 = p1, p1 = p2;
                }
              if (n == 1)
                p0 = 1;
              dp = n * (z * p1 - p0) / (z * z - 1);
              const double d = p1 / dp;
              z -= d;
              if (std::abs(d) < 1e-16)
                break;
            }
          // recompute the derivative at the converged root for the weight
          double p0 = 1, p1 = z;
          for (unsigned k = 2; k <= n; ++k)
            {
              const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
              p0 = p1, p1 = p2;
            }
          dp = n * (z * p1 - p0) / (z * z - 1);
          x[i] = 0.5 * (1 - z);                  // map [-1,1] → [0,1]
          w[i] = 1.0 / ((1 - z * z) * dp * dp);  // 2/((1−z²)P'²), halved for [0,1]
        }
    }

    Vec3 point(const Face &f, const Shape &s)
    {
      Vec3 x = Vec3::Zero();
      for (unsigned k = 0; k < s.n; ++k)
        x += s.N[k] * Vec3(f.X[k][0], f.X[k][1], f.X[k][2]);
      return x;
    }

    void tangents(const Face &f, const Shape &s, Vec3 &ta, Vec3 &tb)
    {
      ta.setZero(), tb.setZero();
      for (unsigned k = 0; k < s.n; ++k)
        {
          const Vec3 X(f.X[k][0], f.X[k][1], f.X[k][2]);
          ta += s.Na[k] * X;
          tb += s.Nb[k] * X;
        }
    }

    std::string face_name(const char *which, std::size_t i)
    {
      return std::string(which) + " face " + std::to_string(i);
    }

    /// Node count, sizes and finiteness; the area check needs the quadrature and follows.
    void check_face(const Face &f, const char *which, std::size_t i)
    {
      if (f.nodes.size() != 4 && f.nodes.size() != 9)
        throw std::invalid_argument("mortar: " + face_name(which, i) + " has " +
                                    std::to_string(f.nodes.size()) +
                                    " nodes; allowed are 4 (bilinear) or 9 (biquadratic)");
      if (f.X.size() != f.nodes.size())
        throw std::invalid_argument("mortar: " + face_name(which, i) + " has " +
                                    std::to_string(f.nodes.size()) + " node ids but " +
                                    std::to_string(f.X.size()) + " positions");
      for (const auto &X : f.X)
        for (double c : X)
          if (!std::isfinite(c))
            throw std::invalid_argument("mortar: " + face_name(which, i) +
                                        " has a non-finite node position");
    }

    /// Throws unless the face's area is clearly positive relative to its size (a face whose
    /// nodes collapse to a point or a line has zero area, and its Me would be singular).
    void check_area(const Face &f, double area, const char *which, std::size_t i)
    {
      Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
      for (const auto &X : f.X)
        for (int d = 0; d < 3; ++d)
          lo[d] = std::min(lo[d], X[d]), hi[d] = std::max(hi[d], X[d]);
      const double diag2 = (hi - lo).squaredNorm();
      if (!(area > 1e-12 * diag2))
        throw std::invalid_argument("mortar: " + face_name(which, i) + " is degenerate (area " +
                                    std::to_string(area) + " m² for a bounding-box diagonal of " +
                                    std::to_string(std::sqrt(diag2)) + " m)");
    }

    /// Master faces in a uniform bucket grid over their bounding boxes inflated by
    /// max_distance: any master point within max_distance of x lies in such a box, so the
    /// cell of x lists every face that can accept it.
    class MasterSearch
    {
    public:
      MasterSearch(const std::vector<Face> &faces, double max_distance)
        : faces_(faces)
      {
        const std::size_t n = faces.size();
        lo_.resize(n), hi_.resize(n);
        Vec3 all_lo = Vec3::Constant(std::numeric_limits<double>::infinity()), all_hi = -all_lo;
        double mean_extent = 0;
        for (std::size_t i = 0; i < n; ++i)
          {
            Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
            for (const auto &X : faces[i].X)
              for (int d = 0; d < 3; ++d)
                lo[d] = std::min(lo[d], X[d]), hi[d] = std::max(hi[d], X[d]);
            // Q2 edges bulge beyond their nodes by at most ¼ of the midpoint's offset from
            // the chord; a margin of ¼ of the node box covers that comfortably for sane faces.
            const Vec3 margin = Vec3::Constant(0.25 * (hi - lo).maxCoeff());
            lo_[i] = lo - margin, hi_[i] = hi + margin;
            lo = lo_[i] - Vec3::Constant(max_distance), hi = hi_[i] + Vec3::Constant(max_distance);
            all_lo = all_lo.cwiseMin(lo), all_hi = all_hi.cwiseMax(hi);
            mean_extent += (hi - lo).maxCoeff() / double(n);
          }
        if (n == 0)
          return;
        origin_ = all_lo;
        // Cell ≈ one inflated face; coarsen if the grid would have far more cells than faces
        // (a thin surface in a big box), so memory stays O(n).
        double h = std::max(mean_extent, 1e-300);
        const Vec3 span = (all_hi - all_lo).cwiseMax(Vec3::Constant(1e-300));
        const double limit = 8.0 * double(n) + 64;
        for (;;)
          {
            for (int d = 0; d < 3; ++d)
              dims_[d] = std::max<long>(1, long(std::ceil(span[d] / h)));
            if (double(dims_[0]) * dims_[1] * dims_[2] <= limit)
              break;
            h *= 1.5;
          }
        h_ = h;
        // CSR: count, prefix sum, fill.
        const std::size_t n_cells = std::size_t(dims_[0] * dims_[1] * dims_[2]);
        start_.assign(n_cells + 1, 0);
        for (int pass = 0; pass < 2; ++pass)
          {
            std::vector<std::size_t> fill;
            if (pass == 1)
              {
                for (std::size_t c = 0; c < n_cells; ++c)
                  start_[c + 1] += start_[c];
                items_.resize(start_[n_cells]);
                fill.assign(start_.begin(), start_.end() - 1);
              }
            for (std::size_t i = 0; i < n; ++i)
              {
                const Vec3 md = Vec3::Constant(max_distance);
                const auto a = cell_index(lo_[i] - md), b = cell_index(hi_[i] + md);
                for (long z = a[2]; z <= b[2]; ++z)
                  for (long y = a[1]; y <= b[1]; ++y)
                    for (long x = a[0]; x <= b[0]; ++x)
                      {
                        const std::size_t c = std::size_t((z * dims_[1] + y) * dims_[0] + x);
                        if (pass == 0)
                          ++start_[c + 1];
                        else
                          items_[fill[c]++] = unsigned(i);
                      }
              }
          }
      }

      /// Calls visit(face index) for each master face whose box the segment
      /// x ± max_distance·n crosses (only those can hold the projection).
      template <typename Visit>
      void for_candidates(const Vec3 &x, const Vec3 &n, double max_distance, Visit &&visit) const
      {
        if (faces_.empty())
          return;
        for (int d = 0; d < 3; ++d)
          if (x[d] < origin_[d] || x[d] > origin_[d] + h_ * dims_[d])
            return;
        const auto c = cell_index(x);
        const std::size_t cell = std::size_t((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
        for (std::size_t j = start_[cell]; j < start_[cell + 1]; ++j)
          {
            const unsigned i = items_[j];
            // slab test of the segment x + t n, t ∈ [−max_distance, max_distance]
            double t0 = -max_distance, t1 = max_distance;
            for (int d = 0; d < 3 && t0 <= t1; ++d)
              {
                if (n[d] == 0)
                  {
                    if (x[d] < lo_[i][d] || x[d] > hi_[i][d])
                      t0 = 1, t1 = 0;
                    continue;
                  }
                double ta = (lo_[i][d] - x[d]) / n[d], tb = (hi_[i][d] - x[d]) / n[d];
                if (ta > tb)
                  std::swap(ta, tb);
                t0 = std::max(t0, ta), t1 = std::min(t1, tb);
              }
            if (t0 <= t1)
              visit(i);
          }
      }

    private:
      std::array<long, 3> cell_index(const Vec3 &x) const
      {
        std::array<long, 3> c;
        for (int d = 0; d < 3; ++d)
          c[d] = std::clamp(long(std::floor((x[d] - origin_[d]) / h_)), 0L, dims_[d] - 1);
        return c;
      }

      const std::vector<Face> &faces_;
      std::vector<Vec3> lo_, hi_;
      Vec3 origin_ = Vec3::Zero();
      double h_ = 1;
      std::array<long, 3> dims_{{1, 1, 1}};
      std::vector<std::size_t> start_;
      std::vector<unsigned> items_;
    };

    /// Newton on X_master(a,b) + g n − x = 0 for (a, b, g), started at the face centre.
    /// Returns false if it does not converge in 30 steps, leaves the face far behind, or ends
    /// outside [0,1]² (tolerance 1e-9) or beyond max_distance.
    bool project(const Face &f, const Vec3 &x, const Vec3 &n, double max_distance, double &a,
                 double &b, double &g)
    {
      const unsigned nn = unsigned(f.nodes.size());
      Shape s;
      a = 0.5, b = 0.5;
      eval_shape(nn, a, b, s);
      g = n.dot(x - point(f, s));
      // The step tolerance in g is relative to the face size (round-off of the positions).
      const double size =
        (Vec3(f.X[0][0], f.X[0][1], f.X[0][2]) - Vec3(f.X[3][0], f.X[3][1], f.X[3][2])).norm();
      for (int it = 0; it < 30; ++it)
        {
          eval_shape(nn, a, b, s);
          Vec3 ta, tb;
          tangents(f, s, ta, tb);
          const Vec3 F = point(f, s) + g * n - x;
          Eigen::Matrix3d J;
          J.col(0) = ta, J.col(1) = tb, J.col(2) = n;
          const double det = J.determinant();
          // A master face (nearly) parallel to the projection direction cannot be hit.
          if (!(std::abs(det) > 1e-12 * ta.norm() * tb.norm()))
            return false;
          const Vec3 d = -J.inverse() * F;
          a += d[0], b += d[1], g += d[2];
          if (!(std::abs(a - 0.5) < 10 && std::abs(b - 0.5) < 10))
            return false;  // diverging or a root far outside: not this face
          // Newton converges quadratically, so a step below 1e-10 leaves an error ~1e-20; a
          // tighter test could stall on round-off for faces far from the origin.
          if (std::abs(d[0]) + std::abs(d[1]) < 1e-10 && std::abs(d[2]) < 1e-10 * size)
            {
              const double tol = 1e-9;
              return a >= -tol && a <= 1 + tol && b >= -tol && b <= 1 + tol &&
                     std::abs(g) <= max_distance;
            }
        }
      return false;
    }

    /// Per slave face: master node → column, and the local M (slave face node × column).
    struct LocalM
    {
      std::vector<long> columns;
      std::vector<std::array<double, max_nodes>> values;
      /// master face → its nodes' columns, cached because consecutive quadrature points
      /// mostly hit the same master face.
      std::vector<std::pair<unsigned, std::array<unsigned, max_nodes>>> face_cols;

      void clear() { columns.clear(), values.clear(), face_cols.clear(); }

      const std::array<unsigned, max_nodes> &cols_of(unsigned mf, const Face &f)
      {
        for (const auto &fc : face_cols)
          if (fc.first == mf)
            return fc.second;
        std::array<unsigned, max_nodes> c{};
        for (std::size_t k = 0; k < f.nodes.size(); ++k)
          {
            const auto it = std::find(columns.begin(), columns.end(), f.nodes[k]);
            if (it != columns.end())
              c[k] = unsigned(it - columns.begin());
            else
              {
                c[k] = unsigned(columns.size());
                columns.push_back(f.nodes[k]);
                values.push_back({});
              }
          }
        face_cols.emplace_back(mf, c);
        return face_cols.back().second;
      }
    };

    /// The options' ranges (std::invalid_argument naming the field and its range).
    void check_options(const Options &options)
    {
      if (!(options.max_distance > 0) || !std::isfinite(options.max_distance))
        throw std::invalid_argument(
          "mortar: Options::max_distance = " + std::to_string(options.max_distance) +
          " m; allowed is (0, inf) m");
      if (options.subdivisions < 1 || options.subdivisions > 1000)
        throw std::invalid_argument("mortar: Options::subdivisions = " +
                                    std::to_string(options.subdivisions) + "; allowed is 1..1000");
      if (options.gauss_points < 1 || options.gauss_points > 20)
        throw std::invalid_argument("mortar: Options::gauss_points = " +
                                    std::to_string(options.gauss_points) + "; allowed is 1..20");

      // Me of a 9-node face is singular unless the rule has ≥ 3 distinct points per direction
      // (then ψ would be garbage without any error); 4-node faces need 2, but one limit is simpler.
      if (options.subdivisions * options.gauss_points < 3)
        throw std::invalid_argument("mortar: Options::subdivisions × gauss_points = " +
                                    std::to_string(options.subdivisions * options.gauss_points) +
                                    " points per direction; at least 3 are needed for a regular "
                                    "mass matrix of a 9-node face");
    }

    /// Slave node id → index into the result; each normal must be a unit vector, each id
    /// listed once.
    std::unordered_map<long, std::size_t> index_slave_nodes(
      const std::vector<SlaveNode> &slave_nodes)
    {
      std::unordered_map<long, std::size_t> index;
      for (std::size_t i = 0; i < slave_nodes.size(); ++i)
        {
          const auto &n = slave_nodes[i].normal;
          const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
          if (!(len > 0.5 && len < 2))
            throw std::invalid_argument("mortar: slave node " + std::to_string(slave_nodes[i].id) +
                                        " has a normal of length " + std::to_string(len) +
                                        "; a unit vector is expected");
          if (!index.emplace(slave_nodes[i].id, i).second)
            throw std::invalid_argument("mortar: slave node " + std::to_string(slave_nodes[i].id) +
                                        " is listed twice");
        }
      return index;
    }

    /// The iterated Gauss rule on [0,1]: points qa and weights qw (summing to 1).
    void iterated_gauss_rule(const Options &options, std::vector<double> &qa,
                             std::vector<double> &qw)
    {
      std::vector<double> gx, gw;
      gauss_legendre(options.gauss_points, gx, gw);
      for (unsigned s = 0; s < options.subdivisions; ++s)
        for (unsigned i = 0; i < gx.size(); ++i)
          qa.push_back((s + gx[i]) / options.subdivisions),
            qw.push_back(gw[i] / options.subdivisions);
    }

    /// Master faces: structure and area (a 3×3 Gauss rule suffices to see a zero area).
    void check_master_faces(const std::vector<Face> &master_faces)
    {
      for (std::size_t i = 0; i < master_faces.size(); ++i)
        {
          const Face &f = master_faces[i];
          check_face(f, "master", i);
          std::vector<double> x3, w3;
          gauss_legendre(3, x3, w3);
          double area = 0;
          Shape s;
          for (unsigned i1 = 0; i1 < 3; ++i1)
            for (unsigned i2 = 0; i2 < 3; ++i2)
              {
                eval_shape(unsigned(f.nodes.size()), x3[i1], x3[i2], s);
                Vec3 ta, tb;
                tangents(f, s, ta, tb);
                area += w3[i1] * w3[i2] * ta.cross(tb).norm();
              }
          check_area(f, area, "master", i);
        }
    }

    /// One slave face's quadrature on the iterated rule (qa, qw): per point its shape, position,
    /// unit normal oriented by the caller's node normals and weight; and the face's dual basis
    /// ψ_k = Σ_l A_kl N_l with D_e,k = ∫ N_k. Throws std::invalid_argument for a degenerate face
    /// or normals (nearly) tangent to it.
    struct SlaveFaceRule
    {
      std::vector<Shape> shape;
      std::vector<Vec3> xq, nq;
      std::vector<double> wq;
      Eigen::VectorXd De;
      Eigen::MatrixXd A;
    };

    void slave_face_rule(const Face &f, const std::size_t e,
                         const std::array<Vec3, max_nodes> &normal, const std::vector<double> &qa,
                         const std::vector<double> &qw, SlaveFaceRule &r)
    {
      const unsigned nn = unsigned(f.nodes.size());
      const std::size_t n_q1 = qa.size(), n_q = n_q1 * n_q1;
      std::vector<Shape> &shape = r.shape;
      std::vector<Vec3> &xq = r.xq, &nq = r.nq;
      std::vector<double> &wq = r.wq;
      // Quadrature points, weights and area first (a degenerate face is reported as such,
      // not as a normal problem), then the oriented normals, D_e and Me.
      double area = 0;
      for (std::size_t i = 0, q = 0; i < n_q1; ++i)
        for (std::size_t j = 0; j < n_q1; ++j, ++q)
          {
            Shape &s = shape[q];
            eval_shape(nn, qa[i], qa[j], s);
            Vec3 ta, tb;
            tangents(f, s, ta, tb);
            nq[q] = ta.cross(tb);  // unnormalised here
            xq[q] = point(f, s);
            wq[q] = qw[i] * qw[j] * nq[q].norm();
            area += wq[q];
          }
      check_area(f, area, "slave", e);

      Eigen::VectorXd De = Eigen::VectorXd::Zero(nn);
      Eigen::MatrixXd Me = Eigen::MatrixXd::Zero(nn, nn);
      for (std::size_t q = 0; q < n_q; ++q)
        {
          const Shape &s = shape[q];
          const double Jq = nq[q].norm();
          Vec3 n_interp = Vec3::Zero();
          for (unsigned k = 0; k < nn; ++k)
            n_interp += s.N[k] * normal[k];
          // Orientation from the caller's node normals, so the sign of the face
          // parametrisation does not matter and curved faces use their true normal.
          const double cosine = Jq > 0 ? nq[q].dot(n_interp) / (Jq * n_interp.norm()) : 0.0;
          if (Jq > 0 && !(std::abs(cosine) > 1e-3))
            throw std::invalid_argument(
              "mortar: slave face " + std::to_string(e) +
              ": the node normals are (nearly) tangent to the face or cancel out "
              "(cosine to the face normal " +
              std::to_string(cosine) + ")");
          nq[q] = Jq > 0 ? Vec3((cosine > 0 ? 1.0 : -1.0) * nq[q] / Jq) : Vec3::Zero();
          for (unsigned k = 0; k < nn; ++k)
            {
              De[k] += wq[q] * s.N[k];
              for (unsigned l = 0; l < nn; ++l)
                Me(k, l) += wq[q] * s.N[k] * s.N[l];
            }
        }

      // Dual basis ψ_k = Σ_l A_kl N_l, A = diag(D_e) Me⁻¹: ∫ψ_k N_l = δ_kl D_e,k with the
      // same quadrature, so biorthogonality holds to round-off.
      const Eigen::LDLT<Eigen::MatrixXd> ldlt(Me);
      const Eigen::MatrixXd A = De.asDiagonal() * ldlt.solve(Eigen::MatrixXd::Identity(nn, nn));
      if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > 1e-12) || !A.allFinite())
        throw std::invalid_argument("mortar: slave face " + std::to_string(e) +
                                    " has a singular mass matrix (degenerate geometry)");
      r.De = De;
      r.A = A;
    }

    /// The couplings from the accumulated rows: C_sm = M_sm / D_s (entries below 1e-14 of D
    /// dropped), the weighted gap G_s / D_s, complete where every quadrature point of the
    /// node's faces found a master.
    std::vector<Coupling> finish_couplings(const std::vector<SlaveNode> &slave_nodes,
                                           std::vector<std::vector<std::pair<long, double>>> &M,
                                           const std::vector<double> &D,
                                           const std::vector<double> &G,
                                           const std::vector<char> &incomplete,
                                           const std::vector<char> &on_face)
    {
      std::vector<Coupling> out(slave_nodes.size());
      for (std::size_t i = 0; i < slave_nodes.size(); ++i)
        {
          Coupling &c = out[i];
          c.node = slave_nodes[i].id;
          c.weight = D[i];
          c.complete = on_face[i] && !incomplete[i];
          c.gap = D[i] > 0 ? G[i] / D[i] : 0.0;
          auto &row = M[i];
          std::sort(row.begin(), row.end(),
                    [](const auto &x, const auto &y) { return x.first < y.first; });
          for (std::size_t j = 0; j < row.size();)
            {
              const long id = row[j].first;
              double sum = 0;
              for (; j < row.size() && row[j].first == id; ++j)
                sum += row[j].second;
              if (D[i] > 0 && std::abs(sum / D[i]) >= 1e-14)
                c.masters.emplace_back(id, sum / D[i]);
            }
          std::vector<std::pair<long, double>>().swap(row);
        }
      return out;
    }
  }  // namespace

  std::vector<Coupling> couple(const std::vector<Face> &slave_faces,
                               const std::vector<SlaveNode> &slave_nodes,
                               const std::vector<Face> &master_faces, const Options &options)
  {
    check_options(options);

    const std::unordered_map<long, std::size_t> index = index_slave_nodes(slave_nodes);

    std::vector<double> qa, qw;
    iterated_gauss_rule(options, qa, qw);
    const std::size_t n_q1 = qa.size();

    check_master_faces(master_faces);
    const MasterSearch search(master_faces, options.max_distance);

    std::vector<std::vector<std::pair<long, double>>> M(slave_nodes.size());
    std::vector<double> D(slave_nodes.size(), 0.0), G(slave_nodes.size(), 0.0);
    std::vector<char> incomplete(slave_nodes.size(), 0), on_face(slave_nodes.size(), 0);

    // Per-face work arrays, reused.
    const std::size_t n_q = n_q1 * n_q1;
    SlaveFaceRule rule;
    rule.shape.resize(n_q);
    rule.xq.resize(n_q);
    rule.nq.resize(n_q);
    rule.wq.resize(n_q);
    LocalM local;

    for (std::size_t e = 0; e < slave_faces.size(); ++e)
      {
        const Face &f = slave_faces[e];
        check_face(f, "slave", e);
        const unsigned nn = unsigned(f.nodes.size());
        std::array<std::size_t, max_nodes> node{};
        std::array<Vec3, max_nodes> normal;
        for (unsigned k = 0; k < nn; ++k)
          {
            const auto it = index.find(f.nodes[k]);
            if (it == index.end())
              throw std::invalid_argument("mortar: slave face " + std::to_string(e) + " has node " +
                                          std::to_string(f.nodes[k]) +
                                          " which has no normal in slave_nodes");
            node[k] = it->second;
            on_face[node[k]] = 1;
            const auto &n = slave_nodes[it->second].normal;
            normal[k] = Vec3(n[0], n[1], n[2]);
          }

        slave_face_rule(f, e, normal, qa, qw, rule);
        const std::vector<Shape> &shape = rule.shape;
        const std::vector<Vec3> &xq = rule.xq, &nq = rule.nq;
        const std::vector<double> &wq = rule.wq;
        const Eigen::VectorXd &De = rule.De;
        const Eigen::MatrixXd &A = rule.A;
        for (unsigned k = 0; k < nn; ++k)
          D[node[k]] += De[k];

        local.clear();
        double Ge[max_nodes] = {};
        bool missed[max_nodes] = {};
        for (std::size_t q = 0; q < n_q; ++q)
          {
            const Shape &s = shape[q];
            double psi[max_nodes];
            for (unsigned k = 0; k < nn; ++k)
              {
                psi[k] = 0;
                for (unsigned l = 0; l < nn; ++l)
                  psi[k] += A(k, l) * s.N[l];
              }

            // Closest accepting master face (smallest |g|; several accept at shared edges).
            long best = -1;
            double ba = 0, bb = 0, bg = std::numeric_limits<double>::infinity();
            if (wq[q] > 0)
              search.for_candidates(xq[q], nq[q], options.max_distance, [&](unsigned mf) {
                double a, b, g;
                if (project(master_faces[mf], xq[q], nq[q], options.max_distance, a, b, g) &&
                    std::abs(g) < std::abs(bg))
                  best = mf, ba = a, bb = b, bg = g;
              });
            if (best < 0)
              {
                // ψ is dimensionless and O(1); 1e-10 separates "zero here" from round-off.
                for (unsigned k = 0; k < nn; ++k)
                  if (std::abs(psi[k]) > 1e-10)
                    missed[k] = true;
                continue;
              }
            const Face &mf = master_faces[std::size_t(best)];
            Shape ms;
            eval_shape(unsigned(mf.nodes.size()), std::clamp(ba, 0.0, 1.0),
                       std::clamp(bb, 0.0, 1.0), ms);
            const auto &cols = local.cols_of(unsigned(best), mf);
            for (unsigned m = 0; m < ms.n; ++m)
              {
                auto &v = local.values[cols[m]];
                for (unsigned k = 0; k < nn; ++k)
                  v[k] += wq[q] * psi[k] * ms.N[m];
              }
            for (unsigned k = 0; k < nn; ++k)
              Ge[k] += wq[q] * psi[k] * bg;
          }

        for (unsigned k = 0; k < nn; ++k)
          {
            G[node[k]] += Ge[k];
            if (missed[k])
              incomplete[node[k]] = 1;
            for (std::size_t c = 0; c < local.columns.size(); ++c)
              M[node[k]].emplace_back(local.columns[c], local.values[c][k]);
          }
      }

    return finish_couplings(slave_nodes, M, D, G, incomplete, on_face);
  }
}  // namespace clearjoint::fe::mortar
