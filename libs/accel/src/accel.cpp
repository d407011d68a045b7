// Placeholder until the accel module lands.
