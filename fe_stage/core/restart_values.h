// deal.II's values in a restart file (core/restart_stream.h): a distributed vector's owned
// entries (read back on the same partition of the same mesh), and tensors by their entries.
#pragma once

#include "fe_stage/core/dim.h"
#include "fe_stage/core/restart_stream.h"

#include <deal.II/base/tensor.h>
#include <deal.II/lac/trilinos_vector.h>

#include <algorithm>
#include <string>
#include <vector>

namespace clearjoint::fe::detail
{
  inline void put_owned(RestartWriter &out, const TrilinosWrappers::MPI::Vector &v)
  {
    out.put_vector(std::vector<double>(v.begin(), v.end()));
  }

  /// Into `v`, which has this rank's owned entries already laid out.
  inline void get_owned(RestartReader &in, TrilinosWrappers::MPI::Vector &v,
                        const std::string &what)
  {
    const std::vector<double> values = in.get_vector<double>();
    if (values.size() != v.locally_owned_size())
      in.damaged(what + " has " + std::to_string(values.size()) + " entries on this rank, " +
                 "where this mesh's partition has " + std::to_string(v.locally_owned_size()));
    std::copy(values.begin(), values.end(), v.begin());
  }

  inline void put_tensor(RestartWriter &out, const Tensor<1, dim> &t)
  {
    for (unsigned int c = 0; c < dim; ++c)
      out.put(t[c]);
  }

  inline Tensor<1, dim> get_tensor(RestartReader &in)
  {
    Tensor<1, dim> t;
    for (unsigned int c = 0; c < dim; ++c)
      t[c] = in.get<double>();
    return t;
  }
}  // namespace clearjoint::fe::detail
