"""Alpha modes: density-scaled and anisotropic test radii and the filtrations they give."""
