// CLI11 validators shared by the commands whose options end up in another
// program's input (vsi work's arguments, #SBATCH lines, Kubernetes
// manifests): refused here, with the option named, instead of an array
// whose every task fails or a manifest the server rejects.
#pragma once

#include <CLI/CLI.hpp>

namespace railvsi::cli {

// A finite number in [lo, hi]. CLI11's PositiveNumber lets nan and inf
// through (nan <= 0 is false).
CLI::Validator finite_in(double lo, double hi);
// vsi work --lease-s's range, which vsi slurm and vsi k8s write into the
// commands of their tasks.
inline constexpr double kLeaseMinS = 0.5;
inline constexpr double kLeaseMaxS = 86400.0;
// Non-empty, without blanks or control characters (an #SBATCH value, an image).
CLI::Validator one_word();
// A Kubernetes resource quantity (e.g. 2Gi, 1500M, 3e9), above zero.
CLI::Validator kubernetes_quantity();
// A Kubernetes object name (RFC 1123 subdomain: lower-case letters, digits,
// '-' and '.', at most 253 characters, starting and ending alphanumeric).
CLI::Validator kubernetes_name();

}  // namespace railvsi::cli
