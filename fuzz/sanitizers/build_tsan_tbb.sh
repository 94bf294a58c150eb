#!/usr/bin/env bash
# Builds the installed Debian oneTBB again from its own Debian source package,
# with -fsanitize=thread, into PREFIX, so ThreadSanitizer sees TBB's task
# hand-over and join (make test-tsan; docs/TESTING.md, "TSan and TBB").
#
# Usage: build_tsan_tbb.sh PREFIX
# The source is the exact version of the installed libtbb-dev, downloaded with
# apt-get into a private folder (no change to the system's apt sources, no
# root). Does nothing when PREFIX already holds a build of that version.
set -euo pipefail

prefix=$(realpath -m "$1")
version=$(dpkg-query -W -f='${Version}' libtbb-dev)
stamp="$prefix/debian-version"
if [[ -f "$stamp" && "$(cat "$stamp")" == "$version" && -f "$prefix/lib/libtbb.so.12" ]]; then
  exit 0
fi

work="$prefix-src"
rm -rf "$prefix" "$work"
mkdir -p "$work/lists/partial" "$work/cache/archives/partial"

# deb-src entries for the distribution this machine runs.
. /etc/os-release
keyring=/usr/share/keyrings/debian-archive-keyring.gpg
cat > "$work/sources.list" <<EOF
deb-src [signed-by=$keyring] http://deb.debian.org/debian $VERSION_CODENAME main
deb-src [signed-by=$keyring] http://deb.debian.org/debian $VERSION_CODENAME-updates main
deb-src [signed-by=$keyring] http://deb.debian.org/debian-security $VERSION_CODENAME-security main
EOF
apt_private=(-o "Dir::Etc::SourceList=$work/sources.list" -o Dir::Etc::SourceParts=/dev/null
             -o "Dir::State::Lists=$work/lists" -o "Dir::Cache=$work/cache"
             -o APT::Sandbox::User=root -qq)

echo "Building a ThreadSanitizer libtbb from Debian's onetbb $version into $prefix"
apt-get "${apt_private[@]}" update
(cd "$work" && apt-get "${apt_private[@]}" source --download-only "onetbb=$version")

upstream=${version%-*}
tar -xf "$work"/onetbb_"${upstream#*:}".orig.tar.xz -C "$work"
src=$(find "$work" -maxdepth 1 -type d -name 'oneTBB-*' | head -n1)
tar -xf "$work"/onetbb_"${version#*:}".debian.tar.xz -C "$src"
# Debian's own patches, so the instrumented library is the installed one.
while read -r patch; do
  [[ -z "$patch" || "$patch" == \#* ]] && continue
  patch -s -p1 -d "$src" < "$src/debian/patches/$patch"
done < "$src/debian/patches/series"

cmake -S "$src" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_COMPILER=clang++ -DTBB_SANITIZE=thread \
      -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBBMALLOC_BUILD=OFF -DTBB_STRICT=OFF \
      -DCMAKE_INSTALL_PREFIX="$prefix" > "$work/configure.log"
cmake --build "$work/build" -j "${JOBS:-2}" > "$work/build.log"
cmake --install "$work/build" > "$work/install.log"
echo "$version" > "$stamp"
rm -rf "$work"
