"""The world a plan runs in: scenario, obstacle motion, geometry, raster maps, file schema."""
