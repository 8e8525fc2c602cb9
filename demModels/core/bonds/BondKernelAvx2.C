// The bond kernel for processors with AVX2 (compiled with -mavx2; called only
// where bestBondKernel found AVX2).
#define BOND_KERNEL_NAME bondKernelAvx2
#include "BondKernelBody.H"
