// The audited kernels, instantiated for float and double: compiled to an sm_90
// cubin that check_audit.py reads (no GPU needed).
#include "audit_kernels.cuh"

namespace gpusolve_audit {

// Taking each kernel's address instantiates it, so the cubin holds its SASS.
template <class T>
void instantiate() {
  (void)&each_element<TriadPlain<T>>;
  (void)&each_element<TriadET<T>>;
  (void)&each_element<ContactPlain<T>>;
  (void)&each_element<ContactET<T>>;
  (void)&each_element<ContactETWriteThrough<T>>;
  (void)&each_element<ContactCached<T>>;
  // The same triad and cached contact bodies, the descriptors passed in the
  // other two ways (plain by-value is each_element above).
  (void)&each_element_grid_constant<TriadET<T>>;
  (void)&each_element<InConstant<TriadET<T>>>;
  (void)&each_element_grid_constant<ContactCached<T>>;
  (void)&each_element<InConstant<ContactCached<T>>>;
}

template void instantiate<float>();
template void instantiate<double>();

}  // namespace gpusolve_audit
