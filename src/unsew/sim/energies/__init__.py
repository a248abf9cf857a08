"""One module per energy: membrane, bending, gravity, contact (+friction, projection), spring."""
