#!/usr/bin/env bash
# Usage: tests/blas_order_test.sh EXECUTABLE
#
# CHOLMOD's dgemm must resolve to the optimised BLAS (OpenBLAS), not to the
# reference BLAS that Debian's Ceres links: the first shared library in the
# executable's dynamic section that defines dgemm_ wins, so libopenblas must
# be listed before libblas / libf77blas / libatlas (a sparse Cholesky is
# ~10x slower otherwise).
set -euo pipefail
exe="${1:?usage: $0 EXECUTABLE}"
needed="$(readelf -d "$exe" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')"
first_blas="$(grep -m1 -E '^lib(openblas|blas|f77blas|atlas|cblas)\.' <<<"$needed" || true)"
echo "first BLAS among the shared libraries of $exe: ${first_blas:-none}"
[[ "$first_blas" == libopenblas.* ]]
