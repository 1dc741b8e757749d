#include "laws/confidence_band.h"

#include "common/error.h"

#include <cmath>

namespace clearjoint::laws
{
  std::vector<BandLaw> confidence_band_laws(const LawFile &law, const std::string &source)
  {
    if (!law.diagnostics)
      throw InputError(source, "diagnostics", "null",
                       "a fitted law (with diagnostics) for a confidence band");
    const FitDiagnostics &d = *law.diagnostics;
    const double K = law.law.K, n = law.law.n, sK = d.K_std_error, sn = d.n_std_error;
    const double rho = d.correlation_K_n;
    if (!(sn > 0.0 && sK > 0.0))
      throw InputError(source, "diagnostics.n_std_error", format_value(sn),
                       "> 0 (a band needs a fit with residuals)");
    const double t = (d.n_ci95_high - n) / sn;  // the Student-t factor the fit used
    const double dn = t * sn;
    const double K_ridge = rho * sK / sn * dn;
    const double dK_across = t * sK * std::sqrt(std::max(0.0, 1.0 - rho * rho));
    struct Variant
    {
      const char *name, *source;
      double K, n;
    };
    std::vector<Variant> variants = {{"n_low", "regression", K - K_ridge, n - dn},
                                     {"n_high", "regression", K + K_ridge, n + dn},
                                     {"K_low", "regression", K - dK_across, n},
                                     {"K_high", "regression", K + dK_across, n}};
    if (law.discretisation_error && law.discretisation_error->F_relative > 0.0)
    {
      const double e = law.discretisation_error->F_relative;
      variants.push_back({"mesh_low", "discretisation", K * (1.0 - e), n});
      variants.push_back({"mesh_high", "discretisation", K * (1.0 + e), n});
    }
    std::vector<BandLaw> out;
    for (const auto &v : variants)
    {
      if (!(v.K > 0.0) || !(v.n > 0.0))
        throw InputError(source, std::string("confidence band ") + v.name,
                         "K = " + format_value(v.K) + ", n = " + format_value(v.n),
                         "K > 0 and n > 0", "the fit is too uncertain for a band");
      LawFile b = law;
      b.law = {v.K, v.n};
      b.source_kind = "confidence_band";
      b.source_description =
        std::string(v.source == std::string("regression") ? "95 % confidence-band variant '" :
                                                            "discretisation-error variant '") +
        v.name + "' of " + source + " (see laws/confidence_band.h)";
      b.diagnostics.reset();
      out.push_back({v.name, v.source, b});
    }
    return out;
  }
} // namespace clearjoint::laws
