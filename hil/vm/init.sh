#!/bin/busybox sh
# /init of the vcan micro-VM initramfs (built by hil/vcan-run; docs/can.md#vcan-run).
# Loads SocketCAN + 9p, creates vcan0, mounts the host root read-only and the
# writable shares listed in /job/mounts at their host paths, chroots into the
# host root and runs /job/cmd.sh. Results go to /job (rc, stdout, stderr).
/bin/busybox --install -s /bin
export PATH=/bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
for m in can can-raw can-dev vcan virtio_ring virtio virtio_pci_modern_dev virtio_pci_legacy_dev \
         virtio_pci netfs fscache 9pnet 9pnet_virtio 9p; do
  insmod /modules/$m.ko 2>/dev/null
done
mkdir -p /host /job
opts=trans=virtio,version=9p2000.L,msize=512000
mount -t 9p -o $opts job /job || { echo "vcan-vm: cannot mount job share"; echo o > /proc/sysrq-trigger; }
mount -t 9p -o $opts,ro,cache=loose host /host || { echo "vcan-vm: cannot mount host root" > /job/vm-error; echo o > /proc/sysrq-trigger; }
ip link add dev vcan0 type vcan && ip link set up vcan0 || echo "vcan-vm: vcan0 setup failed" > /job/vm-error
mount --bind /proc /host/proc
mount --bind /sys /host/sys
mount --bind /dev /host/dev
mkdir -p /host/dev/pts /host/dev/shm
mount -t devpts devpts /host/dev/pts
mount -t tmpfs tmpfs /host/dev/shm
mount -t tmpfs tmpfs /host/tmp
while read tag path; do
  [ -n "$tag" ] || continue
  mkdir -p "/host$path" 2>/dev/null
  mount -t 9p -o $opts "$tag" "/host$path" || echo "vcan-vm: cannot mount $path" >> /job/vm-error
done < /job/mounts
# Last, so no writable share (even one of /tmp itself) can hide it.
mkdir -p /host/tmp/.vcan-job
mount --bind /job /host/tmp/.vcan-job
echo up > /job/booted
chroot /host /bin/bash /tmp/.vcan-job/cmd.sh > /job/stdout 2> /job/stderr < /dev/null
echo $? > /job/rc
sync
echo o > /proc/sysrq-trigger
sleep 10
