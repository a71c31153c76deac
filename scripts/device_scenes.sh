# The shared scenes of the GPU run, relative to the data folder: sourced by device_bench.sh
# (what it traces) and device_pack.sh (what it bundles). The README's NAADF table's scenes.
DEVICE_SCENES=(vox/flyingapts.vox vox/minecraft_nether.vox vox/mmmm_scene_church1.vox mesh/sibenik.obj
               mesh/dabrovic_sponza.obj)
