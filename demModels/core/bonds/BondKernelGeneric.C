// The bond kernel for any x86-64 (SSE2), and the run-time choice of kernel.
#define BOND_KERNEL_NAME bondKernelGeneric
#include "BondKernelBody.H"

#include <cstdlib>
#include <cstring>

namespace iceDEM
{

BondKernel bestBondKernel()
{
    const char* forced = std::getenv("ICEDEM_BOND_KERNEL");
    if (forced && std::strcmp(forced, "generic") == 0)
    {
        return bondKernelGeneric;
    }
    return __builtin_cpu_supports("avx2") ? bondKernelAvx2 : bondKernelGeneric;
}

} // namespace iceDEM
