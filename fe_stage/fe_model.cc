// The FE contact model's façade (fe_model.h): run one scene, start MPI, report library versions.
// The model itself is fe_stage/model.h and the files it names (fe_stage/README.md).
#include "fe_stage/fe_model.h"

#include "fe_stage/model.h"
#include "fe_stage/study/study.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/revision.h>

#include <chrono>
#include <cstdlib>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace clearjoint::fe
{
  namespace detail
  {
    Model::Model(const FeScene &scene, const RunOptions &options)
      : scene_(scene)
      , plan_(plan_study(scene))
      , options_(options)
      , comm_(options.comm)
      , bodies_(scene, plan_, options.comm)
      , dofs_(scene, plan_, bodies_, options.comm)
      , contact_(scene, dofs_, options.comm)
      , pairing_(make_contact_pairing(
          {scene_, plan_, bodies_, dofs_, contact_, obstacle_, frame_, options.comm}))
      , material_({scene_, bodies_, dofs_, state_, options.comm})
      , system_(scene, bodies_, dofs_, options.comm)
      , newton_(*this, {scene_, dofs_, system_, state_, contact_, options.comm})
      , contact_solve_({scene_, plan_, bodies_, dofs_, contact_, obstacle_, frame_, system_, state_,
                        solver_, options.comm})
      , pattern_(*this, {scene_, plan_, bodies_, dofs_, contact_, *pairing_, frame_, system_,
                         state_, contact_solve_, options.comm})
      , fields_({scene_, plan_, bodies_, dofs_, state_, contact_, material_.law(), options.comm},
                options.output_dir, options.write_fields)
      , start_(std::chrono::steady_clock::now())
    {
      obstacle_ = plan_.obstacle;  // (the pairing and the contact solve read it by reference)
    }
  }  // namespace detail

  RunResult run_scene(const FeScene &scene, const RunOptions &options)
  {
    detail::Model model(scene, options);
    return model.run();
  }

  namespace
  {
    /// A process that no launcher started (no mpirun, srun) is a one-rank run that talks to no
    /// other process. Open MPI's default start of such a "singleton" spawns a helper daemon
    /// and probes every transport, ~0.55 s of a ~1.15 s fe_stage start-up on the 2-core
    /// machine (docs/benchmarks.md "The pipeline's start and its report"); the isolated
    /// singleton with the self transport skips both. A variable the user has set is kept;
    /// other MPIs ignore them.
    void prefer_isolated_singleton()
    {
      if (launcher_rank().has_value())
        return;
      ::setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
      ::setenv("OMPI_MCA_pml", "ob1", 0);
      ::setenv("OMPI_MCA_btl", "self", 0);
    }
  }  // namespace

  std::optional<int> launcher_rank()
  {
    for (const char *name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
      if (const char *value = std::getenv(name))
        return std::atoi(value);
    return std::nullopt;
  }

  std::shared_ptr<void> make_runtime(int &argc, char **&argv)
  {
    prefer_isolated_singleton();
    return std::make_shared<dealii::Utilities::MPI::MPI_InitFinalize>(argc, argv, 1);
  }

  std::vector<std::pair<std::string, std::string>> fe_library_versions()
  {
    return {{"deal.II", DEAL_II_PACKAGE_VERSION},
            {"deal.II git", DEAL_II_GIT_SHORTREV},
            {"Trilinos", std::to_string(DEAL_II_TRILINOS_VERSION_MAJOR) + "." +
                           std::to_string(DEAL_II_TRILINOS_VERSION_MINOR) + "." +
                           std::to_string(DEAL_II_TRILINOS_VERSION_SUBMINOR)}};
  }
}  // namespace clearjoint::fe
