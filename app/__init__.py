"""Alpha Scoop desktop application (Qt + VTK), a thin layer over `core`."""
