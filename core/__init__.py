"""Alpha Scoop core: pure numpy/scipy alpha-shape computation (no Qt, no VTK)."""
