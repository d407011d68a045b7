// Placeholder until the raytrace module lands.
