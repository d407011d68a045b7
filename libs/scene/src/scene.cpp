// Placeholder until the scene module lands.
