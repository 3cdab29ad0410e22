"""The oracle: property checks that any IFGM, IBA, FGM or Bug implementation can be run against."""
