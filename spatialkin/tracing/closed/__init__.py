"""The pairs that meet in conics, in closed form: plane sections of quadrics, sphere-sphere, split quadric pairs."""
