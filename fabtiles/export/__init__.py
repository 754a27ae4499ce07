"""Writers for each output format. Each module imports its own heavy library lazily."""
