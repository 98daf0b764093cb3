// Reads an LCM log and, for every event, asks lcm-spy's own type database
// (lcm.spy.LCMTypeDatabase, which scans the class path with
// lcm.util.ClassDiscoverer) for the class with the event's fingerprint, then
// decodes the event with it as lcm-spy does. Prints one line per event:
//   CHANNEL CLASS utime=N     or     CHANNEL UNKNOWN fingerprint=HEX
// Exit status 1 if any event could not be found or decoded.
import java.io.ByteArrayInputStream;
import java.io.DataInputStream;
import java.io.EOFException;
import java.lang.reflect.Field;

public class SpyTypeCheck {
  public static void main(String[] args) throws Exception {
    lcm.spy.LCMTypeDatabase database = new lcm.spy.LCMTypeDatabase();
    lcm.logging.Log log = new lcm.logging.Log(args[0], "r");
    int failures = 0;
    while (true) {
      lcm.logging.Log.Event event;
      try {
        event = log.readNext();
      } catch (EOFException end) {
        break;
      }
      DataInputStream in = new DataInputStream(new ByteArrayInputStream(event.data));
      long fingerprint = in.readLong();
      Class<?> type = database.getClassByFingerprint(fingerprint);
      if (type == null) {
        System.out.println(event.channel + " UNKNOWN fingerprint=" + Long.toHexString(fingerprint));
        failures++;
        continue;
      }
      try {
        Object message = type.getConstructor(byte[].class).newInstance((Object) event.data);
        Field utime = type.getField("utime");
        System.out.println(event.channel + " " + type.getName() + " utime=" + utime.getLong(message));
      } catch (Exception e) {
        System.out.println(event.channel + " " + type.getName() + " DECODE_FAILED " + e);
        failures++;
      }
    }
    System.exit(failures == 0 ? 0 : 1);
  }
}
