// Placeholder until the raster3d module lands.
