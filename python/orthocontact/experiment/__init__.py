"""The experiment described: scenario files (scenario), a lab's rig.toml
(rig_setup), and the experiment at one angle as an SSP package (ssp)."""
